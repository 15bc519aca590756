// Cost per point of project (with and without Jacobian) and unproject for the EuRoC pinhole-radtan camera and a
// 120-degree 640x400 fisheye. Points are spread over the whole image so Newton sees corners as well as the centre.
// Run: build-<you>/bin/bench_camera
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "twinslam/camera/camera_model.hpp"

namespace {

using twinslam::CameraIntrinsics;
using twinslam::DistortionModel;

CameraIntrinsics euroc() {
  CameraIntrinsics in;
  in.width = 752;
  in.height = 480;
  in.fu = 458.654;
  in.fv = 457.296;
  in.cu = 367.215;
  in.cv = 248.375;
  in.coefficients = {-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05};
  return in;
}

CameraIntrinsics fisheye120() {
  CameraIntrinsics in;
  in.distortion = DistortionModel::kEquidistant;
  in.width = 640;
  in.height = 400;
  in.fu = in.fv = 306.0;  // ~120 degrees horizontally
  in.cu = 319.5;
  in.cv = 199.5;
  in.coefficients = {0.012, -0.0048, 0.0011, -1.2e-4};
  return in;
}

CameraIntrinsics model(int which) { return which == 0 ? euroc() : fisheye120(); }

struct Points {
  std::vector<Eigen::Vector2d> pixels;
  std::vector<Eigen::Vector3d> p_C;  // the rays of those pixels at random depths
};

Points sample(const twinslam::CameraModel& cam) {
  Points pts;
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(0, cam.width() - 1), v(0, cam.height() - 1), depth(1.0, 30.0);
  for (int i = 0; i < 4096; ++i) {
    const Eigen::Vector2d uv(u(rng), v(rng));
    Eigen::Vector3d f;
    if (!cam.unproject(uv, &f)) continue;
    pts.pixels.push_back(uv);
    pts.p_C.push_back(depth(rng) * f);
  }
  return pts;
}

void BM_Project(benchmark::State& state) {
  const auto cam = twinslam::make_camera(model(static_cast<int>(state.range(0))));
  const bool with_jacobian = state.range(1) != 0;
  const Points pts = sample(*cam);
  Eigen::Vector2d uv;
  twinslam::Matrix23d J;
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(cam->project(pts.p_C[i], &uv, with_jacobian ? &J : nullptr));
    benchmark::DoNotOptimize(uv);
    benchmark::DoNotOptimize(J);
    if (++i == pts.p_C.size()) i = 0;
  }
  state.SetLabel(std::string(state.range(0) == 0 ? "pinhole-radtan" : "fisheye-equidistant") +
                 (with_jacobian ? " +J" : ""));
}
BENCHMARK(BM_Project)->Args({0, 0})->Args({0, 1})->Args({1, 0})->Args({1, 1});

void BM_Unproject(benchmark::State& state) {
  const auto cam = twinslam::make_camera(model(static_cast<int>(state.range(0))));
  const Points pts = sample(*cam);
  Eigen::Vector3d f;
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(cam->unproject(pts.pixels[i], &f));
    benchmark::DoNotOptimize(f);
    if (++i == pts.pixels.size()) i = 0;
  }
  state.SetLabel(state.range(0) == 0 ? "pinhole-radtan" : "fisheye-equidistant");
}
BENCHMARK(BM_Unproject)->Arg(0)->Arg(1);

}  // namespace
