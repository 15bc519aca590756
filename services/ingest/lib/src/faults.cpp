// Sensor fault injection (faults.hpp): the config and the plan of what happens to each replay event.
#include "twinslam/ingest/faults.hpp"

#include <cmath>
#include <map>
#include <sstream>
#include <utility>

#include "twinslam/core/error.hpp"

namespace twinslam::ingest {
namespace {

struct Named {
  const char* key;
  FaultWindow FaultConfig::*window;
};

// Every window with its config key, in the order they apply when windows overlap (first match wins per event).
constexpr Named kWindows[] = {
    {"imu_gap", &FaultConfig::imu_gap},         {"imu_nan", &FaultConfig::imu_nan},
    {"imu_inf", &FaultConfig::imu_inf},         {"imu_duplicate", &FaultConfig::imu_duplicate},
    {"imu_out_of_order", &FaultConfig::imu_out_of_order}, {"frame_drop", &FaultConfig::frame_drop},
    {"frame_black", &FaultConfig::frame_black}, {"frame_saturated", &FaultConfig::frame_saturated},
    {"gnss_jump", &FaultConfig::gnss_jump},
};

bool is_imu(const ReplayEvent& e) { return e.stream == Stream::Imu; }
bool is_frame(const ReplayEvent& e) { return e.stream == Stream::Image || e.stream == Stream::Features; }

// The action of the first window of the event's stream that contains it.
PlannedEvent decide(const ReplayEvent& e, const FaultConfig& c, std::int64_t t0) {
  const auto in = [&](const FaultWindow& w) { return w.contains(e.stamp_ns, t0); };
  if (is_imu(e)) {
    if (in(c.imu_gap)) return {e, FaultAction::kDrop, "imu_gap"};
    if (in(c.imu_nan)) return {e, FaultAction::kNan, "imu_nan"};
    if (in(c.imu_inf)) return {e, FaultAction::kInf, "imu_inf"};
    if (in(c.imu_duplicate)) return {e, FaultAction::kTwice, "imu_duplicate"};
  } else if (is_frame(e)) {
    if (in(c.frame_drop)) return {e, FaultAction::kDrop, "frame_drop"};
    if (in(c.frame_black)) return {e, FaultAction::kBlack, "frame_black"};
    if (in(c.frame_saturated)) return {e, FaultAction::kSaturated, "frame_saturated"};
  } else if (e.stream == Stream::Gnss && in(c.gnss_jump)) {
    return {e, FaultAction::kGnssShift, "gnss_jump"};
  }
  return {e, FaultAction::kPublish, nullptr};
}

}  // namespace

bool FaultWindow::contains(std::int64_t stamp_ns, std::int64_t t0_ns) const {
  if (!enabled()) return false;
  const double t = 1e-9 * static_cast<double>(stamp_ns - t0_ns);
  return t >= at_s && t < at_s + duration_s;
}

bool FaultConfig::any() const {
  for (const Named& n : kWindows) {
    if ((this->*n.window).enabled()) return true;
  }
  return false;
}

void FaultConfig::validate(const std::string& source) const {
  for (const Named& n : kWindows) {
    const FaultWindow& w = this->*n.window;
    const auto bad = [&](const char* key, const char* what) {
      return InputError(where(source, 0, std::string("ingest key 'faults.") + n.key + "." + key + "': " + what));
    };
    if (!w.enabled()) continue;
    if (!(w.duration_s > 0.0) || !std::isfinite(w.duration_s)) throw bad("duration_s", "must be > 0 s");
    if (!std::isfinite(w.east_m)) throw bad("east_m", "must be finite");
  }
}

void bind_fault_config(yaml::Fields& faults_section, FaultConfig& config) {
  for (const Named& n : kWindows) {
    FaultWindow& w = config.*n.window;
    yaml::Fields& f = faults_section.section(n.key);
    f.number("at_s", w.at_s, "s").number("duration_s", w.duration_s, "s");
    if (n.window == &FaultConfig::gnss_jump) f.number("east_m", w.east_m, "m");
  }
}

std::vector<PlannedEvent> plan_faults(const std::vector<ReplayEvent>& events, const FaultConfig& config) {
  std::vector<PlannedEvent> plan;
  plan.reserve(events.size());
  if (events.empty()) return plan;
  const std::int64_t t0 = events.front().stamp_ns;
  // Out of order: within the window, each IMU sample waits for the next one and goes out after it.
  std::size_t held = events.size();  // index into `plan` of an IMU sample held back, or none
  for (const ReplayEvent& e : events) {
    PlannedEvent p = decide(e, config, t0);
    const bool swap = is_imu(e) && p.action == FaultAction::kPublish && config.imu_out_of_order.contains(e.stamp_ns, t0);
    if (swap) p.fault = "imu_out_of_order";
    plan.push_back(p);
    if (!swap) continue;
    if (held == events.size()) {
      held = plan.size() - 1;
    } else {
      std::swap(plan[held], plan.back());
      held = events.size();
    }
  }
  return plan;
}

std::string describe_plan(const std::vector<PlannedEvent>& plan) {
  std::map<std::string, std::pair<std::size_t, const char*>> counts;
  for (const PlannedEvent& p : plan) {
    if (p.fault == nullptr) continue;
    auto& [n, unit] = counts[p.fault];
    ++n;
    unit = is_imu(p.event) ? "IMU samples" : is_frame(p.event) ? "frames" : "GNSS fixes";
  }
  std::ostringstream out;
  for (const auto& [fault, c] : counts) out << (out.tellp() > 0 ? ", " : "") << fault << " " << c.first << " " << c.second;
  return out.str();
}

}  // namespace twinslam::ingest
