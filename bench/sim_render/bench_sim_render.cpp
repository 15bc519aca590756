// Renderer speed (issue 3, item 5: >= 20 frames/s at 640 x 400 so city-loops, ~6000 frames, renders in <= 5 min):
// frames of the default procedural city (600 m, seed 7) from a loops-like pose: 45 m from the tower, 10 m up,
// looking at it. Reports frames/s as the items/s counter. Thread count is the argument.
// If TWINSLAM_SIM_RENDER_PNG is set, the first fisheye frame is written there (to look at).
#include <cstdlib>

#include <benchmark/benchmark.h>
#include <opencv2/imgcodecs.hpp>

#include "../../tests/sim_world/sim_world_test_utils.hpp"
#include "twinslam/sim/world/city.hpp"
#include "twinslam/sim/world/renderer.hpp"

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

void BM_RenderFisheye640x400(benchmark::State& state) { render_frames(state, true); }
void BM_RenderPinhole640x400(benchmark::State& state) { render_frames(state, false); }

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
BENCHMARK(BM_BuildCityAndBvh)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(2);
