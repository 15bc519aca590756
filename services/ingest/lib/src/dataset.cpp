#include "twinslam/ingest/dataset.hpp"

#include <string>

#include "twinslam/core/csv.hpp"
#include "twinslam/core/error.hpp"

namespace twinslam::ingest {
namespace fs = std::filesystem;

namespace {
void require_increasing(const fs::path& file, const CsvRow& row, std::int64_t previous, std::int64_t stamp) {
  if (stamp <= previous) {
    throw InputError(where(file.string(), row.line,
                           "timestamp " + std::to_string(stamp) + " is not after the previous one (" +
                               std::to_string(previous) + ")"));
  }
}

}  // namespace

std::vector<ImuRecord> load_imu_csv(const fs::path& file) {
  std::vector<ImuRecord> out;
  std::int64_t previous = INT64_MIN;
  read_csv(file, 7, [&](const CsvRow& row) {
    ImuRecord r;
    r.stamp_ns = parse_int64(file, row, 0, "timestamp");
    require_increasing(file, row, previous, r.stamp_ns);
    for (int i = 0; i < 3; ++i) r.gyro_radps[i] = parse_double(file, row, 1 + i, "w_RS_S");
    for (int i = 0; i < 3; ++i) r.accel_mps2[i] = parse_double(file, row, 4 + i, "a_RS_S");
    previous = r.stamp_ns;
    out.push_back(r);
  });
  if (out.empty()) throw InputError(where(file.string(), 0, "no IMU samples"));
  return out;
}

namespace {
std::vector<ImageRecord> load_images(const fs::path& file, CameraInput camera) {
  std::vector<ImageRecord> out;
  std::int64_t previous = INT64_MIN;
  const fs::path image_dir = file.parent_path() / "data";
  read_csv(file, 2, [&](const CsvRow& row) {
    ImageRecord r;
    r.stamp_ns = parse_int64(file, row, 0, "timestamp");
    require_increasing(file, row, previous, r.stamp_ns);
    const std::string name(row.cells[1]);
    if (name.empty()) throw InputError(where(file.string(), row.line, "empty image file name"));
    r.file = image_dir / name;
    if (!fs::is_regular_file(r.file)) {
      throw InputError(where(file.string(), row.line, "image file " + r.file.string() + " does not exist"));
    }
    previous = r.stamp_ns;
    out.push_back(std::move(r));
  });
  if (out.empty() && camera == CameraInput::kImages) {
    throw InputError(where(file.string(), 0, "no images listed (a features-only dataset: replay it with --features)"));
  }
  return out;
}

std::vector<GnssRecord> load_gnss(const fs::path& file) {
  std::vector<GnssRecord> out;
  std::int64_t previous = INT64_MIN;
  read_csv(file, 8, [&](const CsvRow& row) {
    GnssRecord r;
    r.stamp_ns = parse_int64(file, row, 0, "timestamp");
    require_increasing(file, row, previous, r.stamp_ns);
    r.latitude_deg = parse_double(file, row, 1, "latitude");
    r.longitude_deg = parse_double(file, row, 2, "longitude");
    r.altitude_m = parse_double(file, row, 3, "altitude");
    r.std_east_m = parse_double(file, row, 4, "std_east");
    r.std_north_m = parse_double(file, row, 5, "std_north");
    r.std_up_m = parse_double(file, row, 6, "std_up");
    const auto sats = parse_int64(file, row, 7, "num_satellites");
    if (r.latitude_deg < -90 || r.latitude_deg > 90 || r.longitude_deg < -180 || r.longitude_deg > 180) {
      throw InputError(where(file.string(), row.line, "latitude/longitude out of range"));
    }
    if (r.std_east_m < 0 || r.std_north_m < 0 || r.std_up_m < 0 || sats < 0 || sats > 255) {
      throw InputError(where(file.string(), row.line, "negative standard deviation or bad satellite count"));
    }
    r.num_satellites = static_cast<int>(sats);
    previous = r.stamp_ns;
    out.push_back(r);
  });
  return out;
}
}  // namespace

Dataset load_dataset(const fs::path& dir, CameraInput camera) {
  if (!fs::is_directory(dir)) throw InputError(where(dir.string(), 0, "dataset folder does not exist"));
  Dataset ds;
  ds.root = fs::absolute(dir);
  const fs::path mav0 = ds.root / "mav0";
  if (!fs::is_directory(mav0)) throw InputError(where(dir.string(), 0, "not a EuRoC dataset (no mav0/ folder)"));
  ds.imu = load_imu_csv(mav0 / "imu0" / "data.csv");
  ds.images = load_images(mav0 / "cam0" / "data.csv", camera);
  if (const fs::path gnss = mav0 / "gnss0" / "data.csv"; fs::exists(gnss)) ds.gnss = load_gnss(gnss);
  return ds;
}

}  // namespace twinslam::ingest
