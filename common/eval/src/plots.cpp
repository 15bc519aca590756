#include "twinslam/eval/plots.hpp"

#include <algorithm>
#include <cstdio>
#include <system_error>

#include "twinslam/core/error.hpp"
#include "twinslam/plot/plot.hpp"

namespace twinslam::eval {
namespace fs = std::filesystem;
namespace {

// Positions of a pose list projected on two axes (0 = x, 1 = y, 2 = z).
plot::Line projection(const std::vector<Eigen::Isometry3d>& T_WB, int a, int b, std::string label, plot::Rgb color) {
  plot::Line line{std::move(label), {}, {}, color, 2};
  for (const auto& T : T_WB) {
    line.x.push_back(T.translation()[a]);
    line.y.push_back(T.translation()[b]);
  }
  return line;
}

plot::LinePlot view(const Trajectory& gt, const std::vector<PlotRun>& runs, int a, int b, const char* title,
                    const char* xlabel, const char* ylabel) {
  plot::LinePlot p;
  p.title = title;
  p.xlabel = xlabel;
  p.ylabel = ylabel;
  p.equal_aspect = true;
  std::vector<Eigen::Isometry3d> T_WB_gt;
  for (const auto& pose : gt.poses) T_WB_gt.push_back(pose.T_XB);
  p.lines.push_back(projection(T_WB_gt, a, b, "ground truth", plot::kBlack));
  for (std::size_t i = 0; i < runs.size(); ++i) {
    p.lines.push_back(projection(runs[i].result->T_WB_est, a, b, runs[i].label + " (" +
                                 to_string(runs[i].result->align) + ")", plot::palette(i)));
  }
  return p;
}

plot::LinePlot over_time(const Trajectory& gt, const std::vector<PlotRun>& runs, bool rotation) {
  plot::LinePlot p;
  p.title = rotation ? "Rotation error (ATE)" : "Position error (ATE)";
  p.xlabel = "time [s]";
  p.ylabel = rotation ? "rotation error [deg]" : "position error [m]";
  p.y_from_zero = true;
  const std::int64_t t0 = gt.poses.front().stamp_ns;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const EvalResult& r = *runs[i].result;
    plot::Line line{runs[i].label, {}, rotation ? r.ate.rot_err_deg : r.ate.pos_err_m, plot::palette(i), 1};
    for (std::int64_t t : r.stamp_ns) line.x.push_back(static_cast<double>(t - t0) * 1e-9);
    p.lines.push_back(std::move(line));
  }
  return p;
}

plot::BoxPlot rpe_boxes(const std::vector<PlotRun>& runs, bool rotation) {
  plot::BoxPlot p;
  p.title = rotation ? "Relative rotation error per segment length" : "Relative translation error per segment length";
  p.xlabel = "segment length [m] (and % of trajectory length)";
  p.ylabel = rotation ? "rotation error [deg/m]" : "translation error [%]";
  // Categories: every segment length that has samples in at least one run, in the order of the first run.
  if (runs.empty()) return p;
  const auto& keys = runs.front().result->rpe;
  std::vector<std::size_t> used;
  for (std::size_t k = 0; k < keys.size(); ++k) {
    for (const auto& run : runs) {
      if (k < run.result->rpe.size() && !run.result->rpe[k].trans_pct.empty()) {
        used.push_back(k);
        break;
      }
    }
  }
  // Shortest segments on the left, whether given in metres or as a fraction of the length.
  std::stable_sort(used.begin(), used.end(),
                   [&](std::size_t a, std::size_t b) { return keys[a].length_m < keys[b].length_m; });
  for (std::size_t k : used) {
    char name[48];
    std::snprintf(name, sizeof(name), keys[k].key.back() == '%' ? "%.0f (%s)" : "%.0f", keys[k].length_m,
                  keys[k].key.c_str());
    p.categories.push_back(name);
  }
  for (std::size_t i = 0; i < runs.size(); ++i) {
    plot::BoxSeries s{runs[i].label, plot::palette(i), {}};
    for (std::size_t k : used) {
      const auto& seg = runs[i].result->rpe[k];
      s.samples.push_back(rotation ? seg.rot_deg_per_m : seg.trans_pct);
    }
    p.series.push_back(std::move(s));
  }
  return p;
}

}  // namespace

std::vector<fs::path> write_eval_plots(const fs::path& dir, const Trajectory& gt, const std::vector<PlotRun>& runs) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir)) throw InputError(where(dir.string(), 0, "cannot create plot folder"));
  std::vector<fs::path> written;
  const auto save = [&](const auto& figure, const char* name) {
    figure.save(dir / name);
    written.push_back(dir / name);
  };
  save(view(gt, runs, 0, 1, "Trajectory, top view", "x [m]", "y [m]"), "trajectory_xy.png");
  save(view(gt, runs, 0, 2, "Trajectory, side view", "x [m]", "z [m]"), "trajectory_xz.png");
  save(over_time(gt, runs, false), "error_position.png");
  save(over_time(gt, runs, true), "error_rotation.png");
  save(rpe_boxes(runs, false), "rpe_translation.png");
  save(rpe_boxes(runs, true), "rpe_rotation.png");
  return written;
}

}  // namespace twinslam::eval
