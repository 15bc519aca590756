// Acceptance (issue 2): `ingest --max` in one process, a subscriber in another; the subscriber receives all 95
// images and every IMU sample of the EuRoC excerpt, in order, bit-identical to the files.
#include <cstring>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "subprocess.hpp"
#include "twinslam/core/csv.hpp"

namespace fs = std::filesystem;
using namespace twinslam;

namespace {
const fs::path kEuroc = fs::path(TWINSLAM_SHARED_DIR) / "data/euroc-v1-01-micro";

template <class T>
bool read(std::ifstream& in, T& v) {
  return static_cast<bool>(in.read(reinterpret_cast<char*>(&v), sizeof(v)));
}
}  // namespace

TEST(Replay, LockstepDeliversEveryImuSampleAndImageBitIdentical) {
  const fs::path out = fs::temp_directory_path() / ("twinslam_replay_" + std::to_string(::getpid()));
  fs::create_directories(out);
  const std::map<std::string, std::string> env{{"TWINSLAM_DOMAIN", std::to_string(test::test_domain())}};
  test::Background sink({test::bin("replay_sink"), "--out", out.string(), "--timeout", "100"}, env);
  const auto ingest = test::run_process(
      {test::bin("twinslam-ingest"), "--dataset", kEuroc.string(), "--max", "--wait-readers", "1"}, env,
      std::chrono::seconds(100));
  ASSERT_EQ(ingest.exit_code, 0) << ingest.err;
  ASSERT_EQ(sink.wait(std::chrono::seconds(30)), 0) << sink.output();

  // IMU: every row of imu0/data.csv, same order, same bits (the file's decimal text parsed once, here, by strtod).
  std::ifstream imu(out / "imu.bin", std::ios::binary);
  std::size_t n = 0;
  read_csv(kEuroc / "mav0/imu0/data.csv", 7, [&](const CsvRow& row) {
    std::int64_t stamp = 0;
    std::uint64_t seq = 0;
    double v[6];
    ASSERT_TRUE(read(imu, stamp) && read(imu, seq)) << "sample " << n << " missing";
    for (double& x : v) ASSERT_TRUE(read(imu, x));
    ASSERT_EQ(stamp, std::stoll(std::string(row.cells[0])));
    ASSERT_EQ(seq, n);
    for (int i = 0; i < 6; ++i) {
      const double expected = std::strtod(std::string(row.cells[1 + i]).c_str(), nullptr);
      ASSERT_EQ(std::memcmp(&expected, &v[i], sizeof(double)), 0) << "row " << row.line << " column " << i + 2;
    }
    ++n;
  });
  EXPECT_EQ(n, 29120u);
  std::int64_t extra;
  EXPECT_FALSE(read(imu, extra)) << "more IMU samples received than in the file";

  // Images: all 95, in order, pixels equal to the decoded PNG.
  std::ifstream img(out / "images.bin", std::ios::binary);
  std::size_t frames = 0;
  read_csv(kEuroc / "mav0/cam0/data.csv", 2, [&](const CsvRow& row) {
    std::int64_t stamp = 0;
    std::uint64_t seq = 0;
    std::uint32_t w = 0, h = 0;
    ASSERT_TRUE(read(img, stamp) && read(img, seq) && read(img, w) && read(img, h)) << "frame " << frames;
    std::vector<unsigned char> pixels(static_cast<std::size_t>(w) * h);
    ASSERT_TRUE(img.read(reinterpret_cast<char*>(pixels.data()), static_cast<std::streamsize>(pixels.size())));
    const cv::Mat expected = cv::imread((kEuroc / "mav0/cam0/data" / std::string(row.cells[1])).string(),
                                        cv::IMREAD_GRAYSCALE);
    ASSERT_EQ(stamp, std::stoll(std::string(row.cells[0])));
    ASSERT_EQ(seq, frames);
    ASSERT_EQ(static_cast<int>(w), expected.cols);
    ASSERT_EQ(static_cast<int>(h), expected.rows);
    ASSERT_TRUE(expected.isContinuous());
    ASSERT_EQ(std::memcmp(pixels.data(), expected.data, pixels.size()), 0) << "frame " << frames;
    ++frames;
  });
  EXPECT_EQ(frames, 95u);
  fs::remove_all(out);
}
