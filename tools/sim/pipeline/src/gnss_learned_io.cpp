// The learned GNSS model's file (mav0/gnss0/learned_model.yaml) and figure (mav0/gnss0/gnss_vs_height.png).
#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <yaml-cpp/yaml.h>

#include "twinslam/core/error.hpp"
#include "twinslam/plot/plot.hpp"
#include "twinslam/sim/gnss_learned.hpp"

namespace twinslam::sim {
namespace {

constexpr int kFormat = 2;  // 2: received_share per height and elevation (1: per elevation)
// The error column is sign(e) ln(1 + |e| / 1 m) of the range error e (error_to_log), not metres.
const std::vector<std::string> kDimensions{"height_m", "elevation_deg", "error_log1p", "cn0_offset_db"};

template <typename Range>
void flow_seq(YAML::Emitter& y, const Range& values) {
  y << YAML::Flow << YAML::BeginSeq;
  for (const double v : values) y << v;
  y << YAML::EndSeq;
}

std::vector<double> as_vector(const Eigen::VectorXd& v) { return std::vector<double>(v.data(), v.data() + v.size()); }

// Reading: every failure names the file and the key.
struct Reader {
  std::string file;
  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw InputError(file + ": " + key + ": " + what);
  }
  YAML::Node at(const YAML::Node& parent, const std::string& key, const std::string& path) const {
    const YAML::Node n = parent[key];
    if (!n) fail(path + key, "missing");
    return n;
  }
  double number(const YAML::Node& n, const std::string& key) const {
    try {
      const double v = n.as<double>();
      if (!std::isfinite(v)) fail(key, "not finite");
      return v;
    } catch (const YAML::Exception&) {
      fail(key, "expected a number");
    }
  }
  std::vector<double> numbers(const YAML::Node& n, const std::string& key, std::size_t size = 0) const {
    if (!n.IsSequence()) fail(key, "expected a list of numbers");
    std::vector<double> out;
    for (std::size_t i = 0; i < n.size(); ++i) out.push_back(number(n[i], key));
    if (size > 0 && out.size() != size) fail(key, "expected " + std::to_string(size) + " numbers");
    return out;
  }
};

// p-quantile of a 1-D Gaussian mixture given by weights, means and standard deviations (bisection on the CDF).
double mixture_quantile(const std::vector<double>& w, const std::vector<double>& mu, const std::vector<double>& sd,
                        double p) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (std::size_t k = 0; k < w.size(); ++k) {
    lo = std::min(lo, mu[k] - 10 * sd[k]);
    hi = std::max(hi, mu[k] + 10 * sd[k]);
  }
  const auto cdf = [&](double x) {
    double c = 0;
    for (std::size_t k = 0; k < w.size(); ++k) c += w[k] * 0.5 * std::erfc(-(x - mu[k]) / (sd[k] * std::sqrt(2.0)));
    return c;
  };
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    (cdf(mid) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

void write_learned_model(const std::filesystem::path& file, const LearnedGnssModel& m) {
  YAML::Emitter y;
  y.SetDoublePrecision(10);
  y << YAML::BeginMap;
  y << YAML::Key << "format" << YAML::Value << kFormat;
  y << YAML::Key << "training" << YAML::Value << YAML::BeginMap;
  y << YAML::Key << "positions" << YAML::Value << m.training_positions;
  y << YAML::Key << "signals" << YAML::Value << m.training_signals;
  y << YAML::Key << "area_m" << YAML::Value;
  flow_seq(y, m.area_W);
  y << YAML::Key << "height_m" << YAML::Value;
  flow_seq(y, m.height_range_m);
  y << YAML::Key << "sky_time_s" << YAML::Value;
  flow_seq(y, m.sky_time_s);
  y << YAML::Key << "elevation_mask_deg" << YAML::Value << m.elevation_mask_deg;
  y << YAML::Key << "seed" << YAML::Value << m.seed;
  y << YAML::EndMap;

  const learn::GpHyperParameters& h = m.satellites.hyper();
  y << YAML::Key << "satellites_gp" << YAML::Value << YAML::BeginMap;
  y << YAML::Key << "kernel" << YAML::Value << "rbf+white";
  y << YAML::Key << "mean" << YAML::Value << h.mean;
  y << YAML::Key << "signal_var" << YAML::Value << h.signal_var;
  y << YAML::Key << "length_scale_m" << YAML::Value << h.length_scale;
  y << YAML::Key << "noise_var" << YAML::Value << h.noise_var;
  y << YAML::Key << "log_marginal_likelihood" << YAML::Value << m.satellites.log_marginal_likelihood();
  y << YAML::Key << "points" << YAML::Value << YAML::BeginSeq;
  for (std::size_t i = 0; i < m.satellites.x().size(); ++i) {
    flow_seq(y, std::vector<double>{m.satellites.x()[i], m.satellites.y()[i], m.satellites.counts()[i]});
  }
  y << YAML::EndSeq << YAML::EndMap;

  y << YAML::Key << "received_share" << YAML::Value << YAML::BeginMap;
  y << YAML::Key << "bin_deg" << YAML::Value << kElevationBinDeg;
  y << YAML::Key << "height_bin_m" << YAML::Value << kShareHeightBinM;
  y << YAML::Key << "share" << YAML::Value << YAML::BeginSeq;
  for (const std::vector<double>& row : m.received_share) flow_seq(y, row);
  y << YAML::EndSeq << YAML::EndMap;

  y << YAML::Key << "errors_gmm" << YAML::Value << YAML::BeginMap;
  y << YAML::Key << "dimensions" << YAML::Value << YAML::Flow << kDimensions;
  y << YAML::Key << "conditioned_on" << YAML::Value << 2;
  y << YAML::Key << "error_range_m" << YAML::Value;
  flow_seq(y, m.error_range_m);
  y << YAML::Key << "cn0_offset_range_db" << YAML::Value;
  flow_seq(y, m.cn0_offset_range_db);
  y << YAML::Key << "components" << YAML::Value << YAML::BeginSeq;
  for (std::size_t k = 0; k < m.errors.components().size(); ++k) {
    const learn::GaussianComponent& c = m.errors.components()[k];
    y << YAML::BeginMap;
    y << YAML::Key << "weight" << YAML::Value << c.weight;
    y << YAML::Key << "nlos_share" << YAML::Value << m.nlos_share[k];
    y << YAML::Key << "mean" << YAML::Value;
    flow_seq(y, as_vector(c.mean));
    y << YAML::Key << "covariance" << YAML::Value << YAML::Flow << YAML::BeginSeq;
    for (Eigen::Index r = 0; r < c.covariance.rows(); ++r) flow_seq(y, as_vector(c.covariance.row(r).transpose()));
    y << YAML::EndSeq << YAML::EndMap;
  }
  y << YAML::EndSeq << YAML::EndMap;

  y << YAML::Key << "generation" << YAML::Value << YAML::BeginMap;
  y << YAML::Key << "count_tau_s" << YAML::Value << m.generation.count_tau_s;
  y << YAML::Key << "error_tau_s" << YAML::Value << m.generation.error_tau_s;
  y << YAML::Key << "selection" << YAML::Value << "pareto-order";
  y << YAML::EndMap;
  y << YAML::EndMap;

  std::ofstream out(file);
  if (!out) throw InputError(file.string() + ": cannot write");
  out << "# twinslam gnss.model learned: the fitted models (docs/CONTRACTS.md, \"learned_model.yaml\")\n"
      << y.c_str() << "\n";
  if (!out) throw InputError(file.string() + ": write failed");
}

LearnedGnssModel read_learned_model(const std::filesystem::path& file) {
  const Reader r{file.string()};
  YAML::Node root;
  try {
    root = YAML::LoadFile(file.string());
  } catch (const YAML::Exception& e) {
    throw InputError(file.string() + ": " + e.what());
  }
  if (!root.IsMap()) r.fail("(top)", "expected a mapping");
  if (r.number(r.at(root, "format", ""), "format") != kFormat) r.fail("format", "expected " + std::to_string(kFormat));
  try {
    const YAML::Node gp = r.at(root, "satellites_gp", "");
    learn::GpHyperParameters h;
    h.mean = r.number(r.at(gp, "mean", "satellites_gp."), "satellites_gp.mean");
    h.signal_var = r.number(r.at(gp, "signal_var", "satellites_gp."), "satellites_gp.signal_var");
    h.length_scale = r.number(r.at(gp, "length_scale_m", "satellites_gp."), "satellites_gp.length_scale_m");
    h.noise_var = r.number(r.at(gp, "noise_var", "satellites_gp."), "satellites_gp.noise_var");
    std::vector<double> x, yv, counts;
    const YAML::Node points = r.at(gp, "points", "satellites_gp.");
    if (!points.IsSequence()) r.fail("satellites_gp.points", "expected a list of [height, signals, positions]");
    for (std::size_t i = 0; i < points.size(); ++i) {
      const std::vector<double> p = r.numbers(points[i], "satellites_gp.points", 3);
      x.push_back(p[0]);
      yv.push_back(p[1]);
      counts.push_back(p[2]);
    }
    LearnedGnssModel m{.satellites = learn::GaussianProcess(x, yv, h, counts)};

    const YAML::Node gmm = r.at(root, "errors_gmm", "");
    const YAML::Node comps = r.at(gmm, "components", "errors_gmm.");
    if (!comps.IsSequence() || comps.size() == 0) r.fail("errors_gmm.components", "expected a list of components");
    std::vector<learn::GaussianComponent> cs;
    for (std::size_t k = 0; k < comps.size(); ++k) {
      const std::string key = "errors_gmm.components[" + std::to_string(k) + "]";
      learn::GaussianComponent c;
      c.weight = r.number(r.at(comps[k], "weight", key + "."), key + ".weight");
      m.nlos_share.push_back(r.number(r.at(comps[k], "nlos_share", key + "."), key + ".nlos_share"));
      const std::vector<double> mean = r.numbers(r.at(comps[k], "mean", key + "."), key + ".mean", 4);
      c.mean = Eigen::Map<const Eigen::VectorXd>(mean.data(), 4);
      const YAML::Node cov = r.at(comps[k], "covariance", key + ".");
      if (!cov.IsSequence() || cov.size() != 4) r.fail(key + ".covariance", "expected 4 rows");
      c.covariance.resize(4, 4);
      for (int row = 0; row < 4; ++row) {
        const std::vector<double> v = r.numbers(cov[row], key + ".covariance", 4);
        for (int col = 0; col < 4; ++col) c.covariance(row, col) = v[static_cast<std::size_t>(col)];
      }
      cs.push_back(std::move(c));
    }
    m.errors = learn::GaussianMixture(std::move(cs));
    const std::vector<double> er = r.numbers(r.at(gmm, "error_range_m", "errors_gmm."), "errors_gmm.error_range_m", 2);
    m.error_range_m = {er[0], er[1]};
    const std::vector<double> cr =
        r.numbers(r.at(gmm, "cn0_offset_range_db", "errors_gmm."), "errors_gmm.cn0_offset_range_db", 2);
    m.cn0_offset_range_db = {cr[0], cr[1]};

    const YAML::Node rs = r.at(root, "received_share", "");
    if (r.number(r.at(rs, "bin_deg", "received_share."), "received_share.bin_deg") != kElevationBinDeg) {
      r.fail("received_share.bin_deg", "expected " + std::to_string(static_cast<int>(kElevationBinDeg)));
    }
    if (r.number(r.at(rs, "height_bin_m", "received_share."), "received_share.height_bin_m") != kShareHeightBinM) {
      r.fail("received_share.height_bin_m", "expected " + std::to_string(static_cast<int>(kShareHeightBinM)));
    }
    const YAML::Node rows = r.at(rs, "share", "received_share.");
    if (!rows.IsSequence() || rows.size() == 0) r.fail("received_share.share", "expected a list of rows per height");
    for (std::size_t i = 0; i < rows.size(); ++i) {
      m.received_share.push_back(r.numbers(rows[i], "received_share.share", i == 0 ? 0 : m.received_share[0].size()));
    }

    const YAML::Node t = r.at(root, "training", "");
    m.training_positions = static_cast<std::size_t>(r.number(r.at(t, "positions", "training."), "training.positions"));
    m.training_signals = static_cast<std::size_t>(r.number(r.at(t, "signals", "training."), "training.signals"));
    const std::vector<double> a = r.numbers(r.at(t, "area_m", "training."), "training.area_m", 4);
    m.area_W = {a[0], a[1], a[2], a[3]};
    const std::vector<double> hr = r.numbers(r.at(t, "height_m", "training."), "training.height_m", 2);
    m.height_range_m = {hr[0], hr[1]};
    const std::vector<double> st = r.numbers(r.at(t, "sky_time_s", "training."), "training.sky_time_s", 2);
    m.sky_time_s = {st[0], st[1]};
    m.elevation_mask_deg = r.number(r.at(t, "elevation_mask_deg", "training."), "training.elevation_mask_deg");
    m.seed = r.at(t, "seed", "training.").as<std::uint64_t>();

    const YAML::Node g = r.at(root, "generation", "");
    m.generation.count_tau_s = r.number(r.at(g, "count_tau_s", "generation."), "generation.count_tau_s");
    m.generation.error_tau_s = r.number(r.at(g, "error_tau_s", "generation."), "generation.error_tau_s");
    if (!(m.generation.count_tau_s > 0) || !(m.generation.error_tau_s > 0)) {
      r.fail("generation", "correlation times must be > 0");
    }
    return m;
  } catch (const YAML::Exception& e) {
    throw InputError(file.string() + ": " + e.what());
  } catch (const InputError& e) {
    const std::string what = e.what();
    if (what.rfind(file.string(), 0) == 0) throw;
    throw InputError(file.string() + ": " + what);  // e.g. the mixture's or the GP's own checks
  }
}

void write_gnss_vs_height_png(const std::filesystem::path& png, const GnssTrainingData& training,
                              const LearnedGnssModel& model, const std::vector<GnssSample>& fixes, double ground_z_m) {
  const plot::Rgb grey{150, 150, 150}, blue{31, 119, 180}, orange{230, 120, 20};
  double top = 1;
  for (const double h : training.heights_m) top = std::max(top, h);
  std::vector<double> grid;
  for (double h = 0; h <= top; h += top / 200) grid.push_back(h);

  // 1. Signals received: samples, GP mean and +-2 sigma (predictive, i.e. with the white noise).
  plot::LinePlot a;
  a.title = "Satellites received vs height (GP)";
  a.xlabel = "height above ground [m]";
  a.ylabel = "signals received [-]";
  a.y_from_zero = true;
  a.width = 760;
  a.height = 600;
  {
    plot::Line samples{"ray-traced samples", training.heights_m, {}, grey, 1, 2};
    for (const int n : training.received) samples.y.push_back(n);
    plot::Line mean{"GP mean", grid, {}, blue, 2}, lo{"GP +-2 sigma", grid, {}, orange, 1},
        hi{"", grid, {}, orange, 1};
    for (const double h : grid) {
      const learn::GpPrediction p = model.satellites.predict(h);
      mean.y.push_back(p.mean);
      lo.y.push_back(p.mean - 2 * std::sqrt(p.var_y));
      hi.y.push_back(p.mean + 2 * std::sqrt(p.var_y));
    }
    a.lines = {samples, mean, lo, hi};
  }

  // 2. A signal's range error: samples, the mixture's median and 5-95 % band given the height (elevation marginal).
  plot::LinePlot b;
  b.title = "Range error of a signal vs height (GMM)";
  b.xlabel = "height above ground [m]";
  b.ylabel = "multipath / NLOS range error [m] (clipped to +-60)";
  b.width = 760;
  b.height = 600;
  {
    plot::Line samples{"ray-traced signals", {}, {}, grey, 1, 1};
    const std::size_t stride = std::max<std::size_t>(1, training.signals.size() / 6000);
    for (std::size_t i = 0; i < training.signals.size(); i += stride) {
      samples.x.push_back(training.signals[i].height_m);
      samples.y.push_back(std::clamp(training.signals[i].error_m, -60.0, 60.0));
    }
    plot::Line med{"GMM median", {}, {}, blue, 2}, p5{"GMM 5 / 95 %", {}, {}, orange, 1}, p95{"", {}, {}, orange, 1};
    for (const double h : grid) {
      const learn::GaussianMixture c = model.errors.conditional(Eigen::VectorXd::Constant(1, h));
      std::vector<double> w, mu, sd;
      for (const auto& comp : c.components()) {
        w.push_back(comp.weight);
        mu.push_back(comp.mean[1]);
        sd.push_back(std::sqrt(comp.covariance(1, 1)));
      }
      med.x.push_back(h);
      p5.x.push_back(h);
      p95.x.push_back(h);
      // Quantiles of the modelled sign(e) ln(1 + |e|) map to those of e (monotone); its mean would not.
      med.y.push_back(error_from_log(mixture_quantile(w, mu, sd, 0.5)));
      p5.y.push_back(std::max(-60.0, error_from_log(mixture_quantile(w, mu, sd, 0.05))));
      p95.y.push_back(std::min(60.0, error_from_log(mixture_quantile(w, mu, sd, 0.95))));
    }
    b.lines = {samples, med, p5, p95};
  }

  // 3. The fix's horizontal error: ray-traced at the training positions, learned along the flight.
  plot::LinePlot c;
  c.title = "Horizontal error of the fix vs height";
  c.xlabel = "height above ground [m]";
  c.ylabel = "horizontal error [m] (clipped to 60)";
  c.y_from_zero = true;
  c.width = 760;
  c.height = 600;
  {
    plot::Line rt{"ray-traced (training positions)", {}, {}, grey, 1, 2};
    for (std::size_t i = 0; i < training.heights_m.size(); ++i) {
      if (!std::isfinite(training.fix_horizontal_m[i])) continue;
      rt.x.push_back(training.heights_m[i]);
      rt.y.push_back(std::min(60.0, training.fix_horizontal_m[i]));
    }
    plot::Line learned{"learned (this flight)", {}, {}, blue, 1, 2};
    for (const GnssSample& f : fixes) {
      learned.x.push_back(f.true_p_W.z() - ground_z_m);
      learned.y.push_back(std::min(60.0, f.bias_W.head<2>().norm()));
    }
    c.lines = {rt, learned};
  }
  cv::Mat img;
  cv::hconcat(std::vector<cv::Mat>{a.render(), b.render(), c.render()}, img);
  if (!cv::imwrite(png.string(), img)) throw InputError(png.string() + ": cannot write");
}

}  // namespace twinslam::sim
