// EuRoC camera sensor.yaml: the real EuRoC file gives the published calibration, malformed files give an InputError
// that names the file and the key, and what we write reads back identically.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "camera_test_util.hpp"
#include "twinslam/camera/sensor_yaml.hpp"
#include "twinslam/core/error.hpp"

namespace twinslam {
namespace {

namespace fs = std::filesystem;

const fs::path kEurocCam0 = fs::path(TWINSLAM_SHARED_DIR) / "data/euroc-v1-01-micro/mav0/cam0/sensor.yaml";

TEST(CameraSensorYaml, ReadsTheRealEurocCam0Calibration) {
  const CameraConfig c = read_camera_sensor_yaml(kEurocCam0);
  const CameraIntrinsics& in = c.intrinsics;
  EXPECT_EQ(in.distortion, DistortionModel::kRadialTangential);
  EXPECT_EQ(in.width, 752);
  EXPECT_EQ(in.height, 480);
  EXPECT_DOUBLE_EQ(in.fu, 458.654);
  EXPECT_DOUBLE_EQ(in.fv, 457.296);
  EXPECT_DOUBLE_EQ(in.cu, 367.215);
  EXPECT_DOUBLE_EQ(in.cv, 248.375);
  EXPECT_DOUBLE_EQ(in.coefficients[0], -0.28340811);
  EXPECT_DOUBLE_EQ(in.coefficients[1], 0.07395907);
  EXPECT_DOUBLE_EQ(in.coefficients[2], 0.00019359);
  EXPECT_DOUBLE_EQ(in.coefficients[3], 1.76187114e-05);
  EXPECT_DOUBLE_EQ(c.rate_hz, 20.0);
  Eigen::Matrix4d T_BC;  // row-major as printed in the file
  T_BC << 0.0148655429818, -0.999880929698, 0.00414029679422, -0.0216401454975,  //
      0.999557249008, 0.0149672133247, 0.025715529948, -0.064676986768,           //
      -0.0257744366974, 0.00375618835797, 0.999660727178, 0.00981073058949,       //
      0.0, 0.0, 0.0, 1.0;
  EXPECT_EQ(c.T_BC.matrix(), T_BC);
  // EuRoC cam0's optical axis z_C is almost the body's z axis.
  EXPECT_GT(c.T_BC.linear().col(2).z(), 0.999);
}

// A fresh temporary folder per test process, removed at the end.
class CameraYamlFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("twinslam_camera_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path write(const std::string& name, const std::string& text) const {
    const fs::path p = dir_ / name;
    std::ofstream(p) << text;
    return p;
  }
  fs::path dir_;
};

// A valid file in the simulator's style; each malformed case replaces one line of it.
const std::string kGood =
    "sensor_type: camera\n"
    "T_BS:\n"
    "  cols: 4\n"
    "  rows: 4\n"
    "  data: [1, 0, 0, 0.1, 0, 1, 0, 0.2, 0, 0, 1, 0.3, 0, 0, 0, 1]\n"
    "rate_hz: 20\n"
    "resolution: [640, 400]\n"
    "camera_model: pinhole\n"
    "intrinsics: [305.5, 305.5, 319.5, 199.5]\n"
    "distortion_model: equidistant\n"
    "distortion_coefficients: [0.01, -0.005, 0.001, -0.0001]\n";

std::string replace_line(const std::string& text, const std::string& starts_with, const std::string& by) {
  const auto at = text.find(starts_with);
  EXPECT_NE(at, std::string::npos) << starts_with;
  const auto end = text.find('\n', at);
  return text.substr(0, at) + by + text.substr(end);
}

struct Malformed {
  std::string name;     // test case name
  std::string line;     // the line of kGood to replace (prefix)
  std::string by;       // replacement ("" deletes the key)
  std::string key;      // the key the message must name
};

void PrintTo(const Malformed& m, std::ostream* os) { *os << m.name; }

class MalformedSensorYaml : public CameraYamlFiles, public ::testing::WithParamInterface<Malformed> {};

TEST_P(MalformedSensorYaml, ThrowsInputErrorNamingFileAndKey) {
  const Malformed& m = GetParam();
  const fs::path file = write(m.name + ".yaml", replace_line(kGood, m.line, m.by));
  try {
    read_camera_sensor_yaml(file);
    FAIL() << "no error for " << m.name;
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(file.string()), std::string::npos) << msg;
    EXPECT_NE(msg.find("'" + m.key + "'"), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << "one line: " << msg;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Cases, MalformedSensorYaml,
    ::testing::Values(
        Malformed{"missing_intrinsics", "intrinsics:", "", "intrinsics"},
        Malformed{"three_intrinsics", "intrinsics:", "intrinsics: [305.5, 305.5, 319.5]", "intrinsics"},
        Malformed{"nan_intrinsic", "intrinsics:", "intrinsics: [.nan, 305.5, 319.5, 199.5]", "intrinsics"},
        Malformed{"text_intrinsic", "intrinsics:", "intrinsics: [305.5, abc, 319.5, 199.5]", "intrinsics"},
        Malformed{"negative_focal", "intrinsics:", "intrinsics: [-305.5, 305.5, 319.5, 199.5]", "intrinsics"},
        Malformed{"five_coefficients", "distortion_coefficients:", "distortion_coefficients: [0, 0, 0, 0, 0]",
                  "distortion_coefficients"},
        Malformed{"inf_coefficient", "distortion_coefficients:", "distortion_coefficients: [0, .inf, 0, 0]",
                  "distortion_coefficients"},
        Malformed{"unknown_distortion", "distortion_model:", "distortion_model: kb8", "distortion_model"},
        Malformed{"missing_distortion", "distortion_model:", "", "distortion_model"},
        Malformed{"omni_camera", "camera_model:", "camera_model: omni", "camera_model"},
        Malformed{"one_number_resolution", "resolution:", "resolution: [640]", "resolution"},
        Malformed{"fractional_resolution", "resolution:", "resolution: [640.5, 400]", "resolution"},
        Malformed{"zero_resolution", "resolution:", "resolution: [0, 400]", "resolution"},
        Malformed{"text_rate", "rate_hz:", "rate_hz: fast", "rate_hz"},
        Malformed{"missing_rate", "rate_hz:", "", "rate_hz"},
        Malformed{"fifteen_T_BS", "  data:", "  data: [1, 0, 0, 0.1, 0, 1, 0, 0.2, 0, 0, 1, 0.3, 0, 0, 0]",
                  "T_BS.data"},
        Malformed{"scaled_rotation", "  data:", "  data: [1.1, 0, 0, 0.1, 0, 1, 0, 0.2, 0, 0, 1, 0.3, 0, 0, 0, 1]",
                  "T_BS"},
        Malformed{"reflection", "  data:", "  data: [-1, 0, 0, 0.1, 0, 1, 0, 0.2, 0, 0, 1, 0.3, 0, 0, 0, 1]",
                  "T_BS"},
        Malformed{"bad_last_row", "  data:", "  data: [1, 0, 0, 0.1, 0, 1, 0, 0.2, 0, 0, 1, 0.3, 0, 0, 1, 1]",
                  "T_BS"},
        Malformed{"three_rows", "  rows:", "  rows: 3", "T_BS"},
        Malformed{"missing_T_BS_data", "  data:", "", "T_BS.data"}),
    [](const auto& info) { return info.param.name; });

TEST_F(CameraYamlFiles, SyntaxErrorsAndMissingFilesNameTheFile) {
  const fs::path bad = write("syntax.yaml", "intrinsics: [1, 2\nresolution: {\n");
  try {
    read_camera_sensor_yaml(bad);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(bad.string() + ":"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("invalid YAML"), std::string::npos) << e.what();
  }
  const fs::path missing = dir_ / "nope.yaml";
  try {
    read_camera_sensor_yaml(missing);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(missing.string()), std::string::npos) << e.what();
  }
  // A list instead of a mapping at the top.
  EXPECT_THROW(read_camera_sensor_yaml(write("list.yaml", "- 1\n- 2\n")), InputError);
}

TEST_F(CameraYamlFiles, ErrorsReportTheLineOfTheBadValue) {
  const fs::path file = write("line.yaml", "%YAML:1.0\n" + replace_line(kGood, "rate_hz:", "rate_hz: -5"));
  try {
    read_camera_sensor_yaml(file);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'rate_hz'"), std::string::npos) << e.what();
  }
  const fs::path file2 = write("line2.yaml", "%YAML:1.0\n" + replace_line(kGood, "intrinsics:", "intrinsics: [1]"));
  try {
    read_camera_sensor_yaml(file2);
    FAIL();
  } catch (const InputError& e) {  // "%YAML:1.0" is line 1, so intrinsics sit on line 10
    EXPECT_NE(std::string(e.what()).find(file2.string() + ":10: key 'intrinsics'"), std::string::npos) << e.what();
  }
}

TEST_F(CameraYamlFiles, AcceptsTheAliasesOfTheDistortionModels) {
  const auto fisheye = read_camera_sensor_yaml(
      write("fisheye.yaml", replace_line(kGood, "distortion_model:", "distortion_model: fisheye")));
  EXPECT_EQ(fisheye.intrinsics.distortion, DistortionModel::kEquidistant);
  const auto radtan = read_camera_sensor_yaml(
      write("radtan.yaml", replace_line(kGood, "distortion_model:", "distortion_model: radtan")));
  EXPECT_EQ(radtan.intrinsics.distortion, DistortionModel::kRadialTangential);
}

TEST_F(CameraYamlFiles, WhatIsWrittenReadsBackIdentically) {
  CameraConfig fisheye;
  fisheye.intrinsics.distortion = DistortionModel::kEquidistant;
  fisheye.intrinsics.width = 640;
  fisheye.intrinsics.height = 400;
  fisheye.intrinsics.fu = 305.57890238734;
  fisheye.intrinsics.fv = 305.1;
  fisheye.intrinsics.cu = 319.5;
  fisheye.intrinsics.cv = 199.5;
  fisheye.intrinsics.coefficients = {0.012, -0.0048, 1e-20, -1.2e-4};
  fisheye.rate_hz = 20.0;
  fisheye.T_BC = Eigen::Translation3d(0.1, -0.02, 1.0 / 3.0) *
                 Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized());
  CameraConfig euroc = read_camera_sensor_yaml(kEurocCam0);
  for (const CameraConfig& c : {fisheye, euroc}) {
    const fs::path file = dir_ / "written.yaml";
    write_camera_sensor_yaml(file, c);
    const CameraConfig back = read_camera_sensor_yaml(file);
    EXPECT_EQ(back.intrinsics.distortion, c.intrinsics.distortion);
    EXPECT_EQ(back.intrinsics.width, c.intrinsics.width);
    EXPECT_EQ(back.intrinsics.height, c.intrinsics.height);
    EXPECT_EQ(back.intrinsics.fu, c.intrinsics.fu);  // bit-exact: shortest round-trip formatting
    EXPECT_EQ(back.intrinsics.fv, c.intrinsics.fv);
    EXPECT_EQ(back.intrinsics.cu, c.intrinsics.cu);
    EXPECT_EQ(back.intrinsics.cv, c.intrinsics.cv);
    EXPECT_EQ(back.intrinsics.coefficients, c.intrinsics.coefficients);
    EXPECT_EQ(back.rate_hz, c.rate_hz);
    EXPECT_EQ(back.T_BC.matrix(), c.T_BC.matrix());
  }
  // The simulator's fisheye is written the Kalibr way.
  write_camera_sensor_yaml(dir_ / "fisheye.yaml", fisheye);
  std::ifstream in(dir_ / "fisheye.yaml");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("camera_model: pinhole\n"), std::string::npos);
  EXPECT_NE(text.find("distortion_model: equidistant\n"), std::string::npos);
}

TEST_F(CameraYamlFiles, WritingAnInvalidConfigOrToAMissingFolderFails) {
  CameraConfig c;
  c.rate_hz = 0.0;
  EXPECT_THROW(write_camera_sensor_yaml(dir_ / "x.yaml", c), InputError);
  EXPECT_THROW(write_camera_sensor_yaml(dir_ / "no/such/dir/x.yaml", CameraConfig{}), InputError);
}

}  // namespace
}  // namespace twinslam
