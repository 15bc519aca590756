#include "twinslam/camera/sensor_yaml.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <vector>

#include "twinslam/core/error.hpp"
#include "twinslam/core/text.hpp"

namespace twinslam {
namespace {

// Reads keys of one file and reports every problem as "FILE:LINE: key 'K': what".
class KeyReader {
 public:
  KeyReader(std::string file, YAML::Node root) : file_(std::move(file)), root_(std::move(root)) {}

  [[noreturn]] void fail(const YAML::Node& node, const std::string& key, const std::string& what) const {
    const std::size_t line = node && node.Mark().line >= 0 ? static_cast<std::size_t>(node.Mark().line) + 1 : 0;
    throw InputError(where(file_, line, "key '" + key + "': " + what));
  }

  YAML::Node get(const YAML::Node& parent, const std::string& key, const std::string& full_key) const {
    const YAML::Node node = parent[key];
    if (!node || node.IsNull()) fail(node, full_key, "missing");
    return node;
  }
  YAML::Node get(const std::string& key) const { return get(root_, key, key); }

  std::string text(const YAML::Node& node, const std::string& key) const {
    if (!node.IsScalar()) fail(node, key, "expected a single value");
    return node.Scalar();
  }

  double number(const YAML::Node& node, const std::string& key) const {
    const std::string raw = text(node, key);
    std::string_view s = trim(raw);
    if (!s.empty() && s.front() == '+') s.remove_prefix(1);
    double value = 0.0;
    const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
    if (s.empty() || ec != std::errc() || ptr != s.data() + s.size()) {
      fail(node, key, "not a number: '" + node.Scalar() + "'");
    }
    if (!std::isfinite(value)) fail(node, key, "not a finite number: '" + node.Scalar() + "'");
    return value;
  }

  int integer(const YAML::Node& node, const std::string& key) const {
    const std::string raw = text(node, key);
    const std::string_view s = trim(raw);
    int value = 0;
    const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
    if (s.empty() || ec != std::errc() || ptr != s.data() + s.size()) {
      fail(node, key, "not an integer: '" + node.Scalar() + "'");
    }
    return value;
  }

  std::vector<double> numbers(const YAML::Node& node, const std::string& key, std::size_t count) const {
    if (!node.IsSequence()) fail(node, key, "expected a list of " + std::to_string(count) + " numbers");
    if (node.size() != count) {
      fail(node, key, "expected " + std::to_string(count) + " numbers, found " + std::to_string(node.size()));
    }
    std::vector<double> out;
    for (const auto& item : node) out.push_back(number(item, key));
    return out;
  }

 private:
  std::string file_;
  YAML::Node root_;
};

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// Shortest text that reads back to the same double, always with a '.' so YAML 1.1 readers (PyYAML) see a float.
std::string yaml_number(double x) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof(buf), x);
  std::string s(buf, res.ptr);
  if (s.find_first_of(".n") == std::string::npos) {  // 'n': inf/nan never reach here (validated), kept for safety
    const auto e = s.find('e');
    s.insert(e == std::string::npos ? s.size() : e, ".0");
  }
  return s;
}

std::string yaml_list(const double* x, std::size_t n) {
  std::string s = "[";
  for (std::size_t i = 0; i < n; ++i) s += (i ? ", " : "") + yaml_number(x[i]);
  return s + "]";
}

}  // namespace

CameraConfig read_camera_sensor_yaml(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::ifstream in(file);
  if (!in) throw InputError(where(name, 0, "cannot open file"));
  std::stringstream buffer;
  buffer << in.rdbuf();
  std::string text = buffer.str();
  // OpenCV FileStorage writes "%YAML:1.0", which is not a valid YAML directive. Blank the line (keep its newline
  // so yaml-cpp's line numbers still match the file).
  if (text.rfind("%YAML:", 0) == 0) text.erase(0, std::min(text.find('\n'), text.size()));

  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError(where(name, static_cast<std::size_t>(std::max(0, e.mark.line)) + 1, "invalid YAML: " + e.msg));
  }
  if (!root.IsMap()) throw InputError(where(name, 0, "expected a mapping of sensor keys"));
  const KeyReader r(name, root);

  CameraConfig config;
  CameraIntrinsics& intr = config.intrinsics;
  const std::string camera_model = lower(r.text(r.get("camera_model"), "camera_model"));
  if (camera_model != "pinhole") {
    r.fail(r.get("camera_model"), "camera_model", "unsupported '" + camera_model + "' (only pinhole)");
  }
  const YAML::Node dist_node = r.get("distortion_model");
  const std::string dist = lower(r.text(dist_node, "distortion_model"));
  if (dist == "radial-tangential" || dist == "radtan") {
    intr.distortion = DistortionModel::kRadialTangential;
  } else if (dist == "equidistant" || dist == "fisheye") {
    intr.distortion = DistortionModel::kEquidistant;
  } else {
    r.fail(dist_node, "distortion_model",
           "unsupported '" + dist + "' (radial-tangential, radtan, equidistant or fisheye)");
  }

  const auto k = r.numbers(r.get("intrinsics"), "intrinsics", 4);
  intr.fu = k[0];
  intr.fv = k[1];
  intr.cu = k[2];
  intr.cv = k[3];
  const auto c = r.numbers(r.get("distortion_coefficients"), "distortion_coefficients", 4);
  std::copy(c.begin(), c.end(), intr.coefficients.begin());

  const YAML::Node res = r.get("resolution");
  if (!res.IsSequence() || res.size() != 2) r.fail(res, "resolution", "expected [width, height]");
  intr.width = r.integer(res[0], "resolution");
  intr.height = r.integer(res[1], "resolution");

  config.rate_hz = r.number(r.get("rate_hz"), "rate_hz");

  const YAML::Node T = r.get("T_BS");
  if (!T.IsMap()) r.fail(T, "T_BS", "expected a mapping with cols, rows and data");
  const int rows = r.integer(r.get(T, "rows", "T_BS.rows"), "T_BS.rows");
  const int cols = r.integer(r.get(T, "cols", "T_BS.cols"), "T_BS.cols");
  if (rows != 4 || cols != 4) r.fail(T, "T_BS", "expected rows: 4 and cols: 4");
  const auto data = r.numbers(r.get(T, "data", "T_BS.data"), "T_BS.data", 16);
  config.T_BC.matrix() = Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(data.data());

  validate(config, name);
  return config;
}

void write_camera_sensor_yaml(const std::filesystem::path& file, const CameraConfig& config) {
  const std::string name = file.string();
  validate(config, name);
  const CameraIntrinsics& in = config.intrinsics;
  const bool radtan = in.distortion == DistortionModel::kRadialTangential;
  std::ofstream out(file);
  if (!out) throw InputError(where(name, 0, "cannot write file"));
  out << "# Camera sensor in the EuRoC ASL format (written by twinslam).\n"
      << "sensor_type: camera\n"
      << "comment: written by twinslam\n\n"
      << "# Sensor extrinsics wrt. the body-frame: T_BS = T_BC (body <- camera), row-major, metres.\n"
      << "T_BS:\n  cols: 4\n  rows: 4\n  data: [";
  const Eigen::Matrix4d& T = config.T_BC.matrix();
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) out << yaml_number(T(i, j)) << (j < 3 ? ", " : i < 3 ? ",\n         " : "]\n\n");
  }
  const double k[4] = {in.fu, in.fv, in.cu, in.cv};
  out << "# Camera specific definitions.\n"
      << "rate_hz: " << yaml_number(config.rate_hz) << "\n"
      << "resolution: [" << in.width << ", " << in.height << "]\n"
      << "camera_model: pinhole\n"
      << "intrinsics: " << yaml_list(k, 4) << " # fu, fv, cu, cv\n"
      << "distortion_model: " << to_string(in.distortion) << "\n"
      << "distortion_coefficients: " << yaml_list(in.coefficients.data(), 4)
      << (radtan ? " # k1, k2, p1, p2\n" : " # k1, k2, k3, k4\n");
  out.close();
  if (!out) throw InputError(where(name, 0, "write failed"));
}

}  // namespace twinslam
