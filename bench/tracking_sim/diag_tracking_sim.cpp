// Diagnoses the wrong tracks bench_tracking_sim counts: error against the simulator's truth by track age, whether
// errors grow gradually (drift) or jump, how many wrong tracks start at a depth silhouette or end occluded, and the
// surface kind each wrong track started on. Same usage as bench_tracking_sim: [t0_s] [frames]; NOISE=<grey levels>.
// Experiments without a rebuild: SS=n renders n x n rays per pixel (area sampling, no staircase edges); frontend
// config overrides ZNCC (ref_min_zncc), REFWIN (ref_window_px, 0 = plain chained KLT), SIGMA (presmooth_sigma_px),
// SPAN (ransac_span_frames), RT (ransac_threshold_px). Not a test: it prints the figures.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>

#include <opencv2/imgproc.hpp>

#include "twinslam/sim/flight_trajectory.hpp"
#include "twinslam/sim/scenario_io.hpp"
#include "twinslam/sim/sim_camera.hpp"
#include "twinslam/sim/world/city.hpp"
#include "twinslam/sim/world/renderer.hpp"
#include "twinslam/tracking/frontend.hpp"

using namespace twinslam;

namespace {

struct Track {
  Eigen::Vector3d p_W;
  bool has_truth = false;
  bool silhouette = false;  // the range varies by > 10 % across the 15 x 15 px window at detection
  int kind = -1;
  double last_err = 0;
  bool was_wrong = false;
  Eigen::Vector3d p_fg_W;   // nearest surface among the rays of the 3 x 3 pixels around the detection
};

struct Bin {
  std::size_t n = 0, wrong = 0;
  std::vector<double> err;
};

int age_bin(std::uint32_t a) {
  if (a <= 2) return 0;
  if (a <= 3) return 1;
  if (a <= 5) return 2;
  if (a <= 10) return 3;
  if (a <= 20) return 4;
  if (a <= 40) return 5;
  return 6;
}
const char* kBinNames[] = {"2", "3", "4-5", "6-10", "11-20", "21-40", ">40"};

}  // namespace

int main(int argc, char** argv) {
  const sim::Scenario scenario = sim::builtin_scenario("city-loops");
  const sim::City city = sim::build_city(scenario.city, scenario.seed);
  const sim::FlightTrajectory flight = sim::make_flight_trajectory(scenario, city.hints);
  const CameraConfig cam_cfg = sim::sim_camera_config(scenario);
  const std::shared_ptr<const CameraModel> camera(make_camera(cam_cfg.intrinsics));
  sim::RenderConfig rcfg;
  if (const char* n = std::getenv("NOISE")) rcfg.noise_sigma = std::atof(n);
  const sim::Renderer renderer(city.mesh, rcfg);
  // SS=n: render n x n rays per pixel and average them (area sampling, as a real sensor integrates light).
  const int ss = std::getenv("SS") ? std::atoi(std::getenv("SS")) : 1;
  CameraIntrinsics hi = cam_cfg.intrinsics;
  hi.width *= ss;
  hi.height *= ss;
  hi.fu *= ss;
  hi.fv *= ss;
  hi.cu = ss * (hi.cu + 0.5) - 0.5;  // pixel centres at integers in both images
  hi.cv = ss * (hi.cv + 0.5) - 0.5;
  const std::shared_ptr<const CameraModel> camera_hi(make_camera(hi));
  {
    double worst = 0;
    for (int v = 0; v < camera->height(); v += 7) {
      for (int u = 0; u < camera->width(); u += 7) {
        Eigen::Vector3d b;
        Eigen::Vector2d uv;
        if (!camera->unproject(Eigen::Vector2d(u, v), &b) || camera->project(b, &uv) != ProjectionStatus::kOk) continue;
        worst = std::max(worst, (uv - Eigen::Vector2d(u, v)).norm());
      }
    }
    std::printf("camera unproject/project round trip: worst %.2e px\n", worst);
  }
  tracking::FrontendConfig fcfg;
  if (const char* z = std::getenv("ZNCC")) fcfg.ref_min_zncc = std::atof(z);
  if (const char* w = std::getenv("REFWIN")) fcfg.ref_window_px = std::atoi(w);
  if (const char* b = std::getenv("SIGMA")) fcfg.presmooth_sigma_px = std::atof(b);
  if (const char* b = std::getenv("SPAN")) fcfg.ransac_span_frames = std::atoi(b);
  if (const char* b = std::getenv("RT")) fcfg.ransac_threshold_px = std::atof(b);
  tracking::Frontend frontend(camera, fcfg);

  std::map<std::uint64_t, Track> truth;
  long lost[6] = {0, 0, 0, 0, 0, 0};
  std::vector<std::uint32_t> lengths;
  std::vector<double> klt_ms, total_ms;
  Bin bins[7];
  std::size_t wrong_but_fg_right = 0;  // wrong, but within 2 px of the near surface's point beside the detection
  std::size_t wrong_total = 0, wrong_sil = 0, wrong_occluded = 0, wrong_jump = 0, wrong_first = 0;
  std::size_t kind_n[4] = {0, 0, 0, 0}, kind_wrong[4] = {0, 0, 0, 0};
  std::vector<double> err_x, err_y;  // signed error of fresh (age 2) tracks, to spot a constant offset
  const double t0 = argc > 1 ? std::atof(argv[1]) : 60.0, dt = 1.0 / scenario.camera.rate_hz;
  const int frames = argc > 2 ? std::atoi(argv[2]) : 80;
  Eigen::Isometry3d T_WC_prev = Eigen::Isometry3d::Identity();
  for (int k = 0; k < frames; ++k) {
    const double t = t0 + k * dt;
    const Eigen::Isometry3d T_WC = flight.at(t).T_WB() * cam_cfg.T_BC;
    cv::Mat image = renderer.render(T_WC, ss > 1 ? *camera_hi : *camera, 1000 + k);
    if (ss > 1) cv::resize(image, image, cv::Size(camera->width(), camera->height()), 0, 0, cv::INTER_AREA);
    // (the frontend presmooths itself: FrontendConfig::presmooth_sigma_px; SIGMA=<px> overrides it)
    const Eigen::Matrix3d R_prev_curr = T_WC_prev.linear().transpose() * T_WC.linear();
    const auto result = frontend.track(static_cast<std::int64_t>(t * 1e9), image, k > 0 ? &R_prev_curr : nullptr);
    T_WC_prev = T_WC;
    lost[0] += result.stats.lost_klt;
    lost[1] += result.stats.lost_fb;
    lost[2] += result.stats.lost_reference;
    lost[3] += result.stats.lost_ransac + result.stats.lost_span;
    lost[4] += result.stats.pruned;
    lost[5] += result.stats.detected;
    klt_ms.push_back(result.timing.klt_ms);
    total_ms.push_back(result.timing.total_ms);
    for (const auto& f : result.features) lengths.push_back(f.track_length);
    for (const auto& f : result.features) {
      auto& tr = truth[f.id];
      if (f.track_length == 1) {
        const Eigen::Vector3d dir_W = T_WC.linear() * f.bearing_C;
        sim::RayHit hit;
        if (renderer.scene().intersect(T_WC.translation(), dir_W.normalized(), 0.0, 5000.0, &hit)) {
          tr.p_W = T_WC.translation() + hit.t_m * dir_W.normalized();
          tr.has_truth = true;
          tr.kind = static_cast<int>(city.mesh.kind[hit.triangle]);
          tr.p_fg_W = tr.p_W;
          double nearest = hit.t_m;
          for (int dv = -1; dv <= 1; ++dv) {
            for (int du = -1; du <= 1; ++du) {
              Eigen::Vector3d b;
              if (!camera->unproject(f.uv + Eigen::Vector2d(du, dv), &b)) continue;
              const Eigen::Vector3d d = (T_WC.linear() * b).normalized();
              sim::RayHit h1;
              if (renderer.scene().intersect(T_WC.translation(), d, 0.0, 5000.0, &h1) && h1.t_m < 0.9 * nearest) {
                nearest = h1.t_m;
                // The foreground point as seen from the detection pixel's ray direction is not defined; take the
                // near surface's point along the near ray (at most 1 px beside the detection).
                tr.p_fg_W = T_WC.translation() + h1.t_m * d;
              }
            }
          }
          // A silhouette: some ray of the KLT window (15 x 15 px) leaves the plane of the centre's surface.
          for (int dv = -7; dv <= 7; dv += 7) {
            for (int du = -7; du <= 7; du += 7) {
              Eigen::Vector3d b;
              if (!camera->unproject(f.uv + Eigen::Vector2d(du, dv), &b)) continue;
              const Eigen::Vector3d d = (T_WC.linear() * b).normalized();
              sim::RayHit h2;
              const bool hit2 = renderer.scene().intersect(T_WC.translation(), d, 0.0, 5000.0, &h2);
              const Eigen::Vector3d q = T_WC.translation() + h2.t_m * d;
              if (!hit2 || std::abs(hit.n_W.dot(q - tr.p_W)) > 0.05 + 0.005 * hit.t_m) tr.silhouette = true;
            }
          }
        }
        continue;
      }
      if (!tr.has_truth) continue;
      Eigen::Vector2d uv;
      if (camera->project(T_WC.inverse() * tr.p_W, &uv) != ProjectionStatus::kOk) continue;
      const double e = (uv - f.uv).norm();
      Bin& b = bins[age_bin(f.track_length)];
      ++b.n;
      b.err.push_back(e);
      ++kind_n[tr.kind];
      if (f.track_length == 2) {
        err_x.push_back(f.uv.x() - uv.x());
        err_y.push_back(f.uv.y() - uv.y());
      }
      Eigen::Vector2d uv_fg;
      const bool fg_ok = camera->project(T_WC.inverse() * tr.p_fg_W, &uv_fg) == ProjectionStatus::kOk &&
                         (uv_fg - f.uv).norm() <= 2.0;
      if (e > 2.0 && fg_ok) ++wrong_but_fg_right;
      if (e > 2.0) {
        ++b.wrong;
        ++wrong_total;
        ++kind_wrong[tr.kind];
        if (tr.silhouette) ++wrong_sil;
        if (!renderer.visible(tr.p_W, T_WC.translation(), 0.05 + 0.01 * (tr.p_W - T_WC.translation()).norm()))
          ++wrong_occluded;
        if (!tr.was_wrong) {
          ++wrong_first;
          if (tr.last_err < 1.0) ++wrong_jump;
        }
        tr.was_wrong = true;
      }
      tr.last_err = e;
    }
  }
  std::printf("age  n  wrong%%  median_err  p90_err\n");
  for (int i = 0; i < 7; ++i) {
    Bin& b = bins[i];
    if (b.n == 0) continue;
    std::sort(b.err.begin(), b.err.end());
    std::printf("%-6s %6zu %6.2f %%  %.3f  %.3f\n", kBinNames[i], b.n, 100.0 * b.wrong / b.n, b.err[b.n / 2],
                b.err[b.n * 9 / 10]);
  }
  auto mean = [](const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x;
    return v.empty() ? 0.0 : s / v.size();
  };
  std::printf("fresh tracks (age 2) mean signed error: du %.3f dv %.3f px (n %zu)\n", mean(err_x), mean(err_y),
              err_x.size());
  std::printf("wrong observations %zu: started at a silhouette %zu, truth occluded now %zu; tracks turning wrong %zu, "
              "of which jumped from < 1 px %zu\n",
              wrong_total, wrong_sil, wrong_occluded, wrong_first, wrong_jump);
  std::printf("wrong observations within 2 px of the occluding (near) surface's point 1 px beside the detection: %zu\n",
              wrong_but_fg_right);
  std::sort(lengths.begin(), lengths.end());
  std::printf("lost per frame: klt %.1f, fb %.1f, reference %.1f, ransac %.1f, pruned %.1f; detected %.1f; median "
              "track length %u\n",
              lost[0] / double(frames), lost[1] / double(frames), lost[2] / double(frames), lost[3] / double(frames),
              lost[4] / double(frames), lost[5] / double(frames), lengths[lengths.size() / 2]);
  std::sort(klt_ms.begin(), klt_ms.end());
  std::sort(total_ms.begin(), total_ms.end());
  std::printf("wall median: klt + reference alignment %.2f ms, frame %.2f ms\n", klt_ms[klt_ms.size() / 2],
              total_ms[total_ms.size() / 2]);
  const char* kinds[] = {"ground", "facade", "roof", "detail"};
  for (int i = 0; i < 4; ++i)
    std::printf("  %-7s %6zu obs, %5.2f %% wrong\n", kinds[i], kind_n[i], 100.0 * kind_wrong[i] / std::max<std::size_t>(1, kind_n[i]));
  return 0;
}
