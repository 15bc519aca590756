// Folder conventions of CONTRACTS.md: a dataset folder holds its ground truth, a run folder its estimate.
#include "twinslam/core/error.hpp"
#include "twinslam/trajectory/io.hpp"

namespace twinslam {
namespace fs = std::filesystem;

Trajectory read_dataset_groundtruth(const fs::path& dir) {
  // groundtruth.tum first: it is what `twinslam sim` writes in W; the EuRoC CSV is the fallback for real sequences.
  if (fs::is_regular_file(dir / "groundtruth.tum")) return read_tum(dir / "groundtruth.tum");
  const fs::path csv = dir / "mav0" / "state_groundtruth_estimate0" / "data.csv";
  if (fs::is_regular_file(csv)) return read_euroc_groundtruth(csv);
  throw InputError(where(dir.string(), 0,
                         "no ground truth (neither groundtruth.tum nor mav0/state_groundtruth_estimate0/data.csv)"));
}

Trajectory read_run_trajectory(const fs::path& dir) {
  const fs::path file = dir / "trajectory.tum";
  if (!fs::is_regular_file(file)) throw InputError(where(dir.string(), 0, "no trajectory.tum in run folder"));
  return read_tum(file);
}

Trajectory read_trajectory_any(const fs::path& path) {
  if (fs::is_directory(path)) {
    if (fs::is_regular_file(path / "trajectory.tum")) return read_run_trajectory(path);
    if (fs::is_regular_file(path / "groundtruth.tum") ||
        fs::is_regular_file(path / "mav0" / "state_groundtruth_estimate0" / "data.csv")) {
      return read_dataset_groundtruth(path);
    }
    throw InputError(where(path.string(), 0,
                           "neither a run folder (trajectory.tum) nor a dataset folder (groundtruth.tum or "
                           "mav0/state_groundtruth_estimate0/data.csv)"));
  }
  if (!fs::exists(path)) throw InputError(where(path.string(), 0, "no such file or folder"));
  if (path.extension() == ".csv") return read_euroc_groundtruth(path);
  return read_tum(path);
}

}  // namespace twinslam
