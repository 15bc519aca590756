// Renderer speed (issue 3, item 5: >= 20 frames/s at 640 x 400 so city-loops, ~6000 frames, renders in <= 5 min):
// frames of the default procedural city (600 m, seed 7) from a loops-like pose: 45 m from the tower, 10 m up,
// looking at it. Reports frames/s as the items/s counter. Thread count is the argument.
// If TWINSLAM_SIM_RENDER_PNG is set, the first fisheye frame is written there (to look at).
#include <algorithm>
#include <cmath>
#include <cstdlib>

#include <benchmark/benchmark.h>
#include <opencv2/imgcodecs.hpp>

#include "../../tests/sim_world/sim_world_test_utils.hpp"
#include "twinslam/sim/world/city.hpp"
#include "twinslam/sim/world/renderer.hpp"
#include "twinslam/sim/world/traffic.hpp"

namespace {

using namespace twinslam::sim;

const City& city() {
  static const City c = build_city(CityConfig{}, 7);
  return c;
}

void render_frames(benchmark::State& state, bool fisheye) {
  RenderConfig config;
  config.threads = static_cast<int>(state.range(0));
  const Renderer renderer(city().mesh, config);
  const auto cam = fisheye ? testing::fisheye_120() : testing::pinhole_90();
  std::uint64_t frame = 0;
  for (auto _ : state) {
    // Circle the tower like the loops trajectory: every frame a new pose, 0.1 m apart.
    const double a = 0.0022 * static_cast<double>(frame);
    const Eigen::Vector3d c_W(45 * std::cos(a), 45 * std::sin(a), 10);
    const cv::Mat image = renderer.render(testing::look_at(c_W, {0, 0, 30}), *cam, frame);
    benchmark::DoNotOptimize(image.data);
    if (frame == 0 && fisheye && std::getenv("TWINSLAM_SIM_RENDER_PNG"))
      cv::imwrite(std::getenv("TWINSLAM_SIM_RENDER_PNG"), image);
    ++frame;
  }
  state.SetItemsProcessed(state.iterations());  // items/s = frames/s
}

// The same frames as the camera of a scenario other than `tiny` takes them (issue 13): rolling shutter (30 us/line),
// 5 ms exposure, 60 cars on the streets (second argument: which of them, bits 1, 2, 4; 7 = all); the camera circles the
// tower at 1.7 m/s on a 30 m circle, inside the ring kept free for the loops flight (the 45 m circle above passes
// within centimetres of trees, whose motion in the image says nothing about a real flight), or, with yaw_dps > 0, also
// turns at up to that rate. Counters: the mean number of sub-exposures the blur needed and the largest pixel motion
// during an exposure.
void render_imperfect(benchmark::State& state, double yaw_dps) {
  const int what = static_cast<int>(state.range(1));
  RenderConfig config;
  config.threads = static_cast<int>(state.range(0));
  const Renderer renderer(city().mesh, config);
  static const Traffic traffic(city().hints, TrafficSimConfig{60, 8.0}, 600, 7);
  const auto cam = testing::fisheye_120();
  std::uint64_t frame = 0;
  double subexposures = 0, motion = 0;
  for (auto _ : state) {
    FrameCapture f;
    f.t_s = 0.05 * static_cast<double>(frame);  // 20 Hz
    f.shutter = {what & 1 ? 30e-6 : 0.0, what & 2 ? 5e-3 : 0.0};
    f.traffic = what & 4 ? &traffic : nullptr;
    f.T_WC = [yaw_dps](double t) {
      const double a = 1.7 / 30 * t;  // 1.7 m/s on a 30 m circle
      const Eigen::Vector3d c_W(30 * std::cos(a), 30 * std::sin(a), 10);
      Eigen::Isometry3d T = testing::look_at(c_W, {0, 0, 30});
      T.linear() = Eigen::AngleAxisd(yaw_dps * M_PI / 180 * std::sin(t), Eigen::Vector3d::UnitZ()) * T.linear();
      return T;
    };
    RenderInfo info;
    const cv::Mat image = renderer.render(f, *cam, frame, &info);
    benchmark::DoNotOptimize(image.data);
    subexposures += info.subexposures;
    motion = std::max(motion, info.motion_px);
    ++frame;
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["subexposures"] = subexposures / std::max<double>(1, static_cast<double>(frame));
  state.counters["max_motion_px"] = motion;
}

void BM_RenderFisheye640x400(benchmark::State& state) { render_frames(state, true); }
void BM_RenderFisheyeImperfect640x400(benchmark::State& state) { render_imperfect(state, 0); }
void BM_RenderFisheyeImperfectTurning640x400(benchmark::State& state) { render_imperfect(state, 60); }
void BM_RenderPinhole640x400(benchmark::State& state) { render_frames(state, false); }

// The cars of one frame as an Embree scene (60 cars, a 17 ms window: readout and exposure), rebuilt every frame.
void BM_TrafficSnapshot(benchmark::State& state) {
  static const Traffic traffic(city().hints, TrafficSimConfig{60, 8.0}, 600, 7);
  double t = 0;
  for (auto _ : state) {
    const auto snapshot = traffic.snapshot(t, t + 0.017);
    benchmark::DoNotOptimize(snapshot.get());
    t += 0.05;
  }
}

void BM_BuildCityAndBvh(benchmark::State& state) {
  for (auto _ : state) {
    const City c = build_city(CityConfig{}, static_cast<std::uint64_t>(state.iterations()));
    const Renderer renderer(c.mesh);
    benchmark::DoNotOptimize(&renderer);
  }
}

}  // namespace

BENCHMARK(BM_RenderFisheye640x400)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_RenderPinhole640x400)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_RenderFisheyeImperfect640x400)
    ->Args({1, 0})->Args({1, 1})->Args({1, 2})->Args({1, 4})->Args({1, 7})->Args({2, 0})->Args({2, 7})
    ->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_RenderFisheyeImperfectTurning640x400)->Args({2, 7})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_TrafficSnapshot)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_BuildCityAndBvh)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(2);
