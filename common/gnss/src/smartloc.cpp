#include "twinslam/gnss/smartloc.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <sstream>

#include "twinslam/core/error.hpp"

namespace twinslam::gnss {
namespace {

using LineHandler = std::function<void(const std::vector<double>& values, std::size_t line)>;

// Calls on_line for each line whose first word is `kind`, with its numbers; checks the count and finiteness and that
// the time (the first number) does not go backwards across these lines.
void read_lines(const std::string& path, const std::string& kind, std::size_t numbers, const LineHandler& on_line) {
  std::ifstream in(path);
  if (!in) throw InputError(where(path, 0, "cannot open file"));
  static const char* const kKnown[] = {"pseudorange3", "point3", "odom3"};
  std::string text;
  double last_t = -INFINITY;
  for (std::size_t line = 1; std::getline(in, text); ++line) {
    std::istringstream words(text);
    std::string first;
    if (!(words >> first)) continue;  // blank line
    if (std::find(std::begin(kKnown), std::end(kKnown), first) == std::end(kKnown)) {
      throw InputError(where(path, line, "unknown line kind '" + first + "' (known: pseudorange3, point3, odom3)"));
    }
    if (first != kind) continue;
    std::vector<double> values;
    std::string word;
    while (words >> word) {
      char* end = nullptr;
      const double v = std::strtod(word.c_str(), &end);
      if (end == word.c_str() || *end != '\0' || !std::isfinite(v)) {
        throw InputError(where(path, line, kind + " value " + std::to_string(values.size() + 1) + ": '" + word +
                                               "' is not a finite number"));
      }
      values.push_back(v);
    }
    if (values.size() != numbers) {
      throw InputError(where(path, line, kind + ": expected " + std::to_string(numbers) + " numbers, got " +
                                             std::to_string(values.size())));
    }
    if (values[0] < last_t) throw InputError(where(path, line, kind + ": time goes backwards"));
    last_t = values[0];
    on_line(values, line);
  }
}

SatSystem system_of(double code, const std::string& path, std::size_t line) {
  for (const SatSystem s : {SatSystem::kGps, SatSystem::kSbas, SatSystem::kGlonass, SatSystem::kGalileo,
                            SatSystem::kQzss, SatSystem::kBeidou}) {
    if (code == static_cast<double>(static_cast<int>(s))) return s;
  }
  throw InputError(where(path, line, "pseudorange3: unknown satellite system " + std::to_string(code) +
                                         " (known: 1 GPS, 2 SBAS, 4 GLONASS, 8 Galileo, 16 QZSS, 32 BeiDou)"));
}

}  // namespace

std::vector<Epoch> read_smartloc_pseudoranges(const std::string& path) {
  std::vector<Epoch> epochs;
  read_lines(path, "pseudorange3", 10, [&](const std::vector<double>& v, std::size_t line) {
    if (!(v[2] > 0)) throw InputError(where(path, line, "pseudorange3: variance must be > 0"));
    if (epochs.empty() || epochs.back().t_s != v[0]) epochs.push_back(Epoch{v[0], {}});
    Pseudorange p;
    p.range_m = v[1];
    p.sigma_m = std::sqrt(v[2]);
    p.satellite_ecef = {v[3], v[4], v[5]};
    // An id beyond int is undefined to convert (found by fuzzing); real ids are small integers (PRN / slot).
    if (!(v[6] >= 0 && v[6] <= 1e6) || v[6] != std::floor(v[6])) {
      throw InputError(where(path, line, "pseudorange3: satellite id must be an integer in [0, 1e6]"));
    }
    p.satellite_id = static_cast<int>(v[6]);
    p.system = system_of(v[7], path, line);
    p.elevation_deg = v[8];
    p.cn0_dbhz = v[9];
    epochs.back().observations.push_back(p);
  });
  if (epochs.empty()) throw InputError(where(path, 0, "no pseudorange3 lines"));
  return epochs;
}

std::vector<TruthPoint> read_smartloc_ground_truth(const std::string& path) {
  std::vector<TruthPoint> out;
  read_lines(path, "point3", 13, [&](const std::vector<double>& v, std::size_t) {
    out.push_back(TruthPoint{v[0], {v[1], v[2], v[3]}});
  });
  if (out.empty()) throw InputError(where(path, 0, "no point3 lines"));
  return out;
}

}  // namespace twinslam::gnss
