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

// `twinslam sim --no-images` lists no image: a feature-track replay takes it, an image replay says what it is.
TEST(Dataset, AFeaturesOnlyDatasetLoadsForAFeatureReplayOnly) {
  const auto dir = test::broken_copy("featuresonly", [](const fs::path& d) {
    std::ofstream(d / "mav0/cam0/data.csv") << "#timestamp [ns],filename\n";
  });
  EXPECT_EQ(test::load_error(dir), (dir / "mav0/cam0/data.csv").string() +
                                       ": no images listed (a features-only dataset: replay it with --features)");
  const auto ds = ingest::load_dataset(dir, ingest::CameraInput::kFeatureTracks);
  EXPECT_TRUE(ds.images.empty());
  EXPECT_EQ(ds.imu.size(), 29120u);
  // Listed images must still exist in a feature replay: a broken dataset stays broken.
  const auto missing = test::broken_copy("featuresmissing", [](const fs::path& d) {
    fs::remove(d / "mav0/cam0/data/1403715273362142976.png");
  });
  EXPECT_THROW(ingest::load_dataset(missing, ingest::CameraInput::kFeatureTracks), InputError);
  fs::remove_all(dir);
  fs::remove_all(missing);
}

TEST(Dataset, UndecodableImageIsAnInputError) {
  const auto dir = test::broken_copy("badpng", [](const fs::path& d) {
    std::ofstream(d / "mav0/cam0/data/1403715273262142976.png") << "not a png";
  });
  const auto ds = ingest::load_dataset(dir);
  EXPECT_THROW(ingest::load_mono8(ds.images.front().file), InputError);
}

TEST(FeatureTracks, GroupsRowsByFrameAndCountsTrackLengths) {
  const fs::path f = test::scratch_dir() / "features.csv";
  std::ofstream(f) << "#t_ns,landmark_id,u,v,u_noisy,v_noisy\n"
                      "100,1,10,20,10.5,20.5\n100,2,30,40,30,40\n"
                      "200,1,11,21,11.5,21.5\n"
                      "300,1,12,22,12,22\n300,2,31,41,31,41\n";
  const auto frames = ingest::load_feature_tracks(f);
  ASSERT_EQ(frames.size(), 3u);
  EXPECT_EQ(frames[0].stamp_ns, 100);
  ASSERT_EQ(frames[2].features.size(), 2u);
  EXPECT_EQ(frames[2].features[0].track_length, 3u);  // landmark 1 in frames 100, 200, 300
  EXPECT_EQ(frames[2].features[1].track_length, 1u);  // landmark 2 missed frame 200: a new track
  EXPECT_DOUBLE_EQ(frames[0].features[0].u, 10.5);    // noisy columns by default
  EXPECT_DOUBLE_EQ(ingest::load_feature_tracks(f, false)[0].features[0].u, 10.0);
}

TEST(FeatureTracks, RejectsFramesOutOfOrderAndDuplicates) {
  const fs::path f = test::scratch_dir() / "features_bad.csv";
  std::ofstream(f) << "200,1,1,1,1,1\n100,1,1,1,1,1\n";
  try {
    ingest::load_feature_tracks(f);
    FAIL() << "accepted a frame going back";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), f.string() + ":2: timestamp 100 goes back (rows must be grouped by frame)");
  }
  std::ofstream(f) << "100,1,1,1,1,1\n100,1,2,2,2,2\n";
  EXPECT_THROW(ingest::load_feature_tracks(f), InputError);
}
