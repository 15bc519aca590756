#include "twinslam/ingest/features.hpp"

#include <string>
#include <unordered_map>
#include <unordered_set>

#include "twinslam/core/csv.hpp"
#include "twinslam/core/error.hpp"

namespace twinslam::ingest {

std::vector<FeatureFrameRecord> load_feature_tracks(const std::filesystem::path& file, bool noisy) {
  std::vector<FeatureFrameRecord> frames;
  std::unordered_set<std::uint64_t> in_frame;
  std::unordered_map<std::uint64_t, std::uint32_t> previous_length, current_length;
  read_csv(file, 6, [&](const CsvRow& row) {
    const std::int64_t stamp = parse_int64(file, row, 0, "timestamp");
    const std::int64_t id = parse_int64(file, row, 1, "landmark_id");
    if (id < 0) throw InputError(where(file.string(), row.line, "negative landmark_id"));
    if (frames.empty() || stamp != frames.back().stamp_ns) {
      if (!frames.empty() && stamp < frames.back().stamp_ns) {
        throw InputError(where(file.string(), row.line,
                               "timestamp " + std::to_string(stamp) + " goes back (rows must be grouped by frame)"));
      }
      frames.push_back({stamp, {}});
      in_frame.clear();
      previous_length = std::move(current_length);
      current_length.clear();
    }
    FeatureObservation obs;
    obs.landmark_id = static_cast<std::uint64_t>(id);
    obs.u = parse_double(file, row, noisy ? 4 : 2, noisy ? "u_noisy" : "u");
    obs.v = parse_double(file, row, noisy ? 5 : 3, noisy ? "v_noisy" : "v");
    if (!in_frame.insert(obs.landmark_id).second) {
      throw InputError(where(file.string(), row.line, "landmark " + std::to_string(id) + " twice in one frame"));
    }
    // A track continues only if the landmark was seen in the immediately preceding frame.
    const auto it = previous_length.find(obs.landmark_id);
    obs.track_length = it == previous_length.end() ? 1 : it->second + 1;
    current_length[obs.landmark_id] = obs.track_length;
    frames.back().features.push_back(obs);
  });
  if (frames.empty()) throw InputError(where(file.string(), 0, "no feature observations"));
  return frames;
}

}  // namespace twinslam::ingest
