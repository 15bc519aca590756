#pragma once
// Where the world no longer matches the twin (issue 16 item 5): evidence from a run's landmarks in W, clustered into
// places with a footprint. Two kinds of evidence, both about geometry only (no image is compared with the map):
//   - an unexplained landmark: farther than min_distance_m from every twin surface. Landmarks sit on real surfaces,
//     so a building missing from the twin, or one standing elsewhere, leaves landmarks on facades the twin lacks;
//   - a sight line through the twin: the camera saw the landmark, so the straight line from where it was seen to the
//     landmark is free space; a twin surface crossing it (with the landmark at least min_distance_m behind it) is
//     geometry the world does not have - a building only the twin has, or the twin's copy of a moved one.
// A place is reported only when its evidence is consistent: enough of it, seen over a span of time (one bad
// triangulation or one keyframe does not make a change).
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "twinslam/twin/mesh.hpp"

namespace twinslam::twin {

struct TwinChangeConfig {
  double min_quality = 0.5;        // landmarks of lower quality (0..1: observations, parallax) are not used
  double min_distance_m = 1.5;     // a landmark this far from every twin surface is unexplained [m]
  double search_radius_m = 10.0;   // farthest surface looked for; beyond, a landmark's distance is this [m]
  double observer_margin_m = 1.0;  // crossings this close to where the landmark was seen from are ignored [m]
  double min_grazing_cos = 0.15;   // crossings of surfaces the line grazes (|cos| to the normal below this) are ignored
  double cluster_radius_m = 4.0;   // evidence within this horizontal distance joins one place [m]
  std::size_t min_evidence = 8;    // landmarks + sight lines a place needs to be reported
  double min_span_s = 3.0;         // ... seen over at least this long [s]
  double min_extent_m = 3.0;       // ... spread over at least this much horizontally (a facade, not a detail) [m]
  void validate() const;           // UsageError naming the key
};

// One landmark as the run estimated it, with where it was seen from.
struct LandmarkSighting {
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();           // the landmark [m]
  Eigen::Vector3d observer_W = Eigen::Vector3d::Zero();    // where it was first seen from [m]
  double t_s = 0;                                          // when [s]
  double quality = 1;                                      // 0..1, the estimator's (Landmark.quality)
};

struct TwinChange {
  std::string kind;  // "missing" (mostly unexplained landmarks), "added" (mostly sight lines), "moved" (both)
  std::vector<Eigen::Vector2d> footprint_W;  // convex hull of the evidence, counter-clockwise [m, E N]
  std::size_t landmarks = 0;                 // unexplained landmarks
  std::size_t sight_lines = 0;               // sight lines through twin surfaces
  double mean_distance_m = 0;   // unexplained landmarks: mean distance to the nearest twin surface, + outside [m]
  double mean_depth_m = 0;      // sight lines: mean depth of the landmark behind the crossed surface [m]
  double first_s = 0, last_s = 0;  // when the evidence was seen [s]
};

struct TwinChanges {
  std::vector<TwinChange> places;  // largest evidence first
  std::size_t landmarks_used = 0;  // finite, of min_quality or better
  std::size_t unexplained = 0;     // evidence in all, reported or not
  std::size_t sight_lines = 0;
};

// The places where the run's landmarks disagree with twin_W (triangles in W). InputError for a twin without
// triangles; UsageError for a bad config.
TwinChanges find_twin_changes(const Mesh& twin_W, const std::vector<LandmarkSighting>& sightings,
                              const TwinChangeConfig& config = {});

}  // namespace twinslam::twin
