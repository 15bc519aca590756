// The estimator's checkpoint file (--checkpoint, issue 14), then the resume planned from what was read at frames
// around its stamp and far from it: read_checkpoint may only refuse with InputError, and a plan it accepts has finite
// sigmas and a finite state (a restarted estimator starts its window from them).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <limits>

#include "harness.hpp"
#include "twinslam/estimator/resume.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace twinslam;
  const auto path = fuzz::write_scratch("estimator.checkpoint.json", data, size);
  return fuzz::expect_input_error_only([&] {
    const auto cp = estimator::read_checkpoint(path);
    if (!cp) std::abort();  // the file exists: "no checkpoint" would lose a flight's state silently
    const estimator::ResumeConfig config;
    for (const std::int64_t frame_ns : {cp->stamp_ns, cp->stamp_ns / 2 + 1'000'000'000, std::int64_t{0},
                                        std::numeric_limits<std::int64_t>::max()}) {
      const auto plan = estimator::plan_resume(*cp, frame_ns, config);
      if (!plan) continue;
      const auto& s = plan->pose_W.sigmas;  // set by every plan: GlobalFusion::start_from weighs T_WL with them
      const bool finite = plan->state_L.v_L.allFinite() && plan->state_L.q_LB.coeffs().allFinite() &&
                          plan->pose_W.p_W.allFinite() && std::isfinite(plan->pose_W.yaw_deg) && s.has_value() &&
                          s->position_m > 0 && std::isfinite(s->position_m) && s->yaw_rad > 0 &&
                          std::isfinite(s->yaw_rad) && std::isfinite(plan->sigmas.velocity_mps);
      if (!finite) std::abort();
    }
  });
}
