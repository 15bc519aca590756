#pragma once
// A recorded or simulated sequence in the EuRoC ASL layout of CONTRACTS.md (gnss0 optional), loaded and validated
// up front: every row parsed, timestamps strictly increasing per stream, every image file present. Replay then
// cannot fail half-way through a flight because of a bad row at minute 4.
#include <cstdint>
#include <filesystem>
#include <vector>

#include <Eigen/Core>

namespace twinslam::ingest {

struct ImuRecord {
  std::int64_t stamp_ns = 0;
  Eigen::Vector3d gyro_radps = Eigen::Vector3d::Zero();   // w_RS_S: angular rate of B in B [rad/s]
  Eigen::Vector3d accel_mps2 = Eigen::Vector3d::Zero();   // a_RS_S: specific force in B [m/s^2]
};

struct ImageRecord {
  std::int64_t stamp_ns = 0;
  std::filesystem::path file;  // absolute path of the PNG
};

struct GnssRecord {
  std::int64_t stamp_ns = 0;
  double latitude_deg = 0, longitude_deg = 0, altitude_m = 0;
  double std_east_m = 0, std_north_m = 0, std_up_m = 0;
  int num_satellites = 0;
};

struct Dataset {
  std::filesystem::path root;
  std::vector<ImuRecord> imu;
  std::vector<ImageRecord> images;   // cam0
  std::vector<GnssRecord> gnss;      // empty when the dataset has no mav0/gnss0
};

// What the camera stream of a replay is made of. A feature-track replay (`--features`) publishes
// mav0/cam0/features.csv and reads no image, so its cam0/data.csv may list none (`twinslam sim --no-images`).
enum class CameraInput { kImages, kFeatureTracks };

// Throws InputError naming the file (and line) on: missing folder or file, malformed row, non-finite value,
// timestamps not strictly increasing, a listed image file that does not exist, no image listed (kImages only).
Dataset load_dataset(const std::filesystem::path& dir, CameraInput camera = CameraInput::kImages);

// Just the IMU file (mav0/imu0/data.csv), with the same checks: for features-only datasets (`sim --no-images`).
std::vector<ImuRecord> load_imu_csv(const std::filesystem::path& file);

}  // namespace twinslam::ingest
