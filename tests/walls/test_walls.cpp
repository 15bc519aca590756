// The walls of docs/ARCHITECTURE.md hold in this source tree, and the checker catches each kind of breach.
#include <gtest/gtest.h>

#include <unistd.h>

#include <fstream>

#include "walls.hpp"

namespace twinslam::testing {
namespace {
namespace fs = std::filesystem;

void write(const fs::path& file, const std::string& text) {
  fs::create_directories(file.parent_path());
  std::ofstream(file) << text;
}

bool mentions(const std::vector<std::string>& v, const std::string& what) {
  for (const auto& s : v) {
    if (s.find(what) != std::string::npos) return true;
  }
  return false;
}

TEST(Walls, TheRepositoryKeepsItsWalls) {
  const auto violations = wall_violations(TWINSLAM_SOURCE_DIR);
  for (const auto& v : violations) ADD_FAILURE() << v;
  EXPECT_TRUE(violations.empty());
}

TEST(Walls, EachBreachIsReportedWithFileAndLine) {
  const fs::path root = fs::temp_directory_path() / ("twinslam_walls_" + std::to_string(::getpid()));
  fs::remove_all(root);
  write(root / "services/tracking/lib/src/a.cpp", "#include <vector>\n#include \"twinslam/estimator/imu_types.hpp\"\n");
  write(root / "services/tracking/lib/CMakeLists.txt", "twinslam_library(x PUBLIC_LINKS twinslam_estimator_core)\n");
  write(root / "services/estimator/lib/src/b.cpp", "#include <opencv2/core.hpp>\n");
  write(root / "services/estimator/node/c.cpp", "#include \"twinslam/estimator/x.hpp\"\n");  // its own: fine
  write(root / "common/core/src/d.cpp", "#include \"twinslam/tiles/tile_grid.hpp\"\n");
  write(root / "services/registration/lib/include/twinslam/registration/e.hpp", "#include <pcl/point_types.h>\n");
  write(root / "services/registration/lib/src/f.cpp", "#include <pcl/point_types.h>\n");  // allowed
  write(root / "services/tiles/lib/src/g.cpp", "#include <pcl/kdtree/kdtree_flann.h>\n");
  const auto v = wall_violations(root);
  fs::remove_all(root);
  EXPECT_TRUE(mentions(v, "services/tracking/lib/src/a.cpp:2: service 'tracking' depends on service 'estimator'"));
  EXPECT_TRUE(mentions(v, "services/tracking/lib/CMakeLists.txt:1: service 'tracking' depends on service 'estimator'"));
  EXPECT_TRUE(mentions(v, "services/estimator/lib/src/b.cpp:1: the estimator library sees bearings"));
  EXPECT_TRUE(mentions(v, "common/core/src/d.cpp:1: common/ depends on service 'tiles'"));
  EXPECT_TRUE(mentions(v, "e.hpp:1: PCL only"));
  EXPECT_TRUE(mentions(v, "services/tiles/lib/src/g.cpp:1: PCL only"));
  EXPECT_FALSE(mentions(v, "c.cpp"));
  EXPECT_FALSE(mentions(v, "f.cpp"));
  EXPECT_EQ(v.size(), 6u);
}

}  // namespace
}  // namespace twinslam::testing
