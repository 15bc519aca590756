#pragma once
// Ideal feature tracks written by `twinslam sim --features` (mav0/cam0/features.csv: t_ns, landmark_id, u, v,
// u_noisy, v_noisy), grouped per frame, so the estimator can be run and tested without the image frontend.
#include <cstdint>
#include <filesystem>
#include <vector>

namespace twinslam::ingest {

struct FeatureObservation {
  std::uint64_t landmark_id = 0;
  double u = 0, v = 0;              // pixel [px]: noisy (default) or noise-free, see load_feature_tracks
  std::uint32_t track_length = 1;   // consecutive frames this landmark has been observed, including this one
};

struct FeatureFrameRecord {
  std::int64_t stamp_ns = 0;
  std::vector<FeatureObservation> features;
};

// Rows must be grouped by frame with increasing stamps, and a landmark appears at most once per frame.
// Throws InputError naming file:line otherwise, or for malformed rows / non-finite pixels.
std::vector<FeatureFrameRecord> load_feature_tracks(const std::filesystem::path& file, bool noisy = true);

}  // namespace twinslam::ingest
