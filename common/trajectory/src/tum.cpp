// TUM RGB-D trajectory format (Sturm et al., IROS 2012): "timestamp tx ty tz qx qy qz qw", timestamp in seconds.
#include <charconv>
#include <cstdio>
#include <cmath>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "checks.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/core/text.hpp"
#include "twinslam/trajectory/io.hpp"

namespace twinslam {
namespace {

// Seconds as decimal text -> nanoseconds, exactly. Parsing through a double would lose ~0.1 us at epoch-sized stamps
// (1.4e9 s has a double resolution of 2.4e-7 s), enough to break a round trip through write_tum.
std::optional<std::int64_t> seconds_text_to_ns(std::string_view s) {
  if (s.find_first_of("eE") != std::string_view::npos) {  // scientific notation: a double is all we can do
    double seconds = 0.0;
    const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), seconds);
    if (ec != std::errc() || ptr != s.data() + s.size() || !std::isfinite(seconds)) return std::nullopt;
    return std::llround(seconds * 1e9);
  }
  bool negative = false;
  if (!s.empty() && (s.front() == '-' || s.front() == '+')) {
    negative = s.front() == '-';
    s.remove_prefix(1);
  }
  const auto dot = s.find('.');
  const std::string_view whole = s.substr(0, dot);
  std::string_view frac = dot == std::string_view::npos ? std::string_view{} : s.substr(dot + 1);
  if (whole.empty() && frac.empty()) return std::nullopt;
  std::int64_t sec = 0;
  if (!whole.empty()) {
    const auto [ptr, ec] = std::from_chars(whole.data(), whole.data() + whole.size(), sec);
    if (ec != std::errc() || ptr != whole.data() + whole.size() || sec > 9'000'000'000LL) return std::nullopt;
  }
  std::int64_t ns = 0;
  int digits = 0;
  bool round_up = false;
  for (std::size_t i = 0; i < frac.size(); ++i) {
    const char c = frac[i];
    if (c < '0' || c > '9') return std::nullopt;
    if (digits < 9) {
      ns = ns * 10 + (c - '0');
      ++digits;
    } else if (digits == 9 && i == 9) {
      round_up = c >= '5';  // round half up on the 10th decimal
    }
  }
  for (; digits < 9; ++digits) ns *= 10;
  const std::int64_t total = sec * 1'000'000'000LL + ns + (round_up ? 1 : 0);
  return negative ? -total : total;
}

std::vector<std::string_view> tokens(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == ',')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != ',') ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

double number(const std::filesystem::path& file, std::size_t line, std::string_view cell, const char* name) {
  double value = 0.0;
  const auto [ptr, ec] = std::from_chars(cell.data(), cell.data() + cell.size(), value);
  if (ec != std::errc() || ptr != cell.data() + cell.size()) {
    throw InputError(where(file.string(), line, std::string(name) + ": not a number: '" + std::string(cell) + "'"));
  }
  if (!std::isfinite(value)) {
    throw InputError(where(file.string(), line, std::string(name) + ": not finite: '" + std::string(cell) + "'"));
  }
  return value;
}

// Shortest text that reads back to the same double (std::to_chars without precision).
std::string exact(double v) {
  char buf[64];
  const auto [ptr, ec] = std::to_chars(buf, buf + sizeof(buf), v);
  return std::string(buf, ptr);
}

}  // namespace

Trajectory read_tum(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(where(file.string(), 0, "cannot open file"));
  Trajectory trajectory;
  trajectory.source = file.string();
  static const char* kNames[] = {"timestamp", "tx", "ty", "tz", "qx", "qy", "qz", "qw"};
  std::string text;
  std::size_t line = 0;
  while (std::getline(in, text)) {
    ++line;
    const std::string_view trimmed = trim(text);
    if (trimmed.empty() || trimmed.front() == '#') continue;
    const auto cells = tokens(trimmed);
    if (cells.size() != 8) {
      throw InputError(where(file.string(), line, "expected 8 values (t tx ty tz qx qy qz qw), found " +
                                                      std::to_string(cells.size())));
    }
    const auto stamp_ns = seconds_text_to_ns(cells[0]);
    if (!stamp_ns) {
      throw InputError(where(file.string(), line, "timestamp: not a number: '" + std::string(cells[0]) + "'"));
    }
    double v[8];
    for (int i = 1; i < 8; ++i) v[i] = number(file, line, cells[i], kNames[i]);
    const Eigen::Quaterniond q_XB(v[7], v[4], v[5], v[6]);  // Eigen order: w, x, y, z
    detail::check_unit_quaternion(file, line, q_XB);
    detail::append_increasing(file, line, trajectory, make_pose(*stamp_ns, Eigen::Vector3d(v[1], v[2], v[3]), q_XB));
  }
  if (in.bad()) throw InputError(where(file.string(), line, "read error"));
  detail::check_not_empty(file, trajectory);
  return trajectory;
}

void write_tum(const std::filesystem::path& file, const Trajectory& trajectory) {
  std::ofstream out(file);
  if (!out) throw InputError(where(file.string(), 0, "cannot write file"));
  out << "# timestamp[s] tx ty tz qx qy qz qw\n";
  char stamp[48];
  for (const auto& pose : trajectory.poses) {
    const std::int64_t ns = pose.stamp_ns;
    const std::int64_t mag = ns < 0 ? -ns : ns;
    std::snprintf(stamp, sizeof(stamp), "%s%lld.%09lld", ns < 0 ? "-" : "",
                  static_cast<long long>(mag / 1'000'000'000LL), static_cast<long long>(mag % 1'000'000'000LL));
    const Eigen::Vector3d p = pose.p_X();
    const Eigen::Quaterniond q = pose.q_XB();
    out << stamp << ' ' << exact(p.x()) << ' ' << exact(p.y()) << ' ' << exact(p.z()) << ' ' << exact(q.x()) << ' '
        << exact(q.y()) << ' ' << exact(q.z()) << ' ' << exact(q.w()) << '\n';
  }
  if (!out) throw InputError(where(file.string(), 0, "write failed"));
}

}  // namespace twinslam
