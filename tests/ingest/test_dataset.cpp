// Dataset loading (EuRoC ASL layout): the real EuRoC excerpt loads completely; each kind of bad input is an
// InputError that names the file and, for rows, the line.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "twinslam/core/error.hpp"
#include "twinslam/ingest/dataset.hpp"
#include "twinslam/ingest/replay.hpp"
#include "dataset_fixture.hpp"

namespace fs = std::filesystem;
using namespace twinslam;

TEST(Dataset, LoadsTheEurocExcerpt) {
  const auto ds = ingest::load_dataset(test::euroc_dir());
  EXPECT_EQ(ds.images.size(), 95u);
  EXPECT_EQ(ds.imu.size(), 29120u);
  EXPECT_TRUE(ds.gnss.empty());
  EXPECT_EQ(ds.imu.front().stamp_ns, 1403715273262142976LL);
  EXPECT_DOUBLE_EQ(ds.imu.front().accel_mps2.x(), 9.0874956666666655);
  EXPECT_EQ(ds.images.front().file.filename(), "1403715273262142976.png");
  const cv::Mat img = ingest::load_mono8(ds.images.front().file);
  EXPECT_EQ(img.cols, 752);
  EXPECT_EQ(img.rows, 480);
}

TEST(Dataset, ReplayOrderIsByTimeWithImuFirstAtEqualStamps) {
  const auto ds = ingest::load_dataset(test::euroc_dir());
  const auto events = ingest::replay_order(ds);
  ASSERT_EQ(events.size(), ds.imu.size() + ds.images.size());
  for (std::size_t i = 1; i < events.size(); ++i) {
    ASSERT_LE(events[i - 1].stamp_ns, events[i].stamp_ns);
    if (events[i - 1].stamp_ns == events[i].stamp_ns) ASSERT_LT(events[i - 1].stream, events[i].stream);
  }
  // The first frame shares its stamp with an IMU sample, which must come first.
  EXPECT_EQ(events[0].stream, ingest::Stream::Imu);
  EXPECT_EQ(events[1].stream, ingest::Stream::Image);
}

TEST(Dataset, MissingFolder) {
  EXPECT_EQ(test::load_error("/nonexistent/dataset"), "/nonexistent/dataset: dataset folder does not exist");
}

TEST(Dataset, MalformedImuRowNamesFileAndLine) {
  const auto dir = test::broken_copy("badrow", [](const fs::path& d) {
    test::replace_line(d / "mav0/imu0/data.csv", 3, "1403715273267142912,0.1,zzz,0.3,9.0,0.1,0.2");
  });
  EXPECT_EQ(test::load_error(dir),
            (dir / "mav0/imu0/data.csv").string() + ":3: column 3 (w_RS_S): not a number: 'zzz'");
}

TEST(Dataset, TimestampsGoingBackwards) {
  const auto dir = test::broken_copy("backwards", [](const fs::path& d) {
    test::replace_line(d / "mav0/cam0/data.csv", 4, "1403715273262142976,1403715273262142976.png");
  });
  EXPECT_EQ(test::load_error(dir), (dir / "mav0/cam0/data.csv").string() +
                                        ":4: timestamp 1403715273262142976 is not after the previous one "
                                        "(1403715273312143104)");
}

TEST(Dataset, MissingImageFile) {
  const auto dir = test::broken_copy("noimage", [](const fs::path& d) {
    fs::remove(d / "mav0/cam0/data/1403715273362142976.png");
  });
  EXPECT_EQ(test::load_error(dir), (dir / "mav0/cam0/data.csv").string() + ":4: image file " +
                                        (dir / "mav0/cam0/data/1403715273362142976.png").string() +
                                        " does not exist");
}

TEST(Dataset, UndecodableImageIsAnInputError) {
  const auto dir = test::broken_copy("badpng", [](const fs::path& d) {
    std::ofstream(d / "mav0/cam0/data/1403715273262142976.png") << "not a png";
  });
  const auto ds = ingest::load_dataset(dir);
  EXPECT_THROW(ingest::load_mono8(ds.images.front().file), InputError);
}
