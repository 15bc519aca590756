// The web view's files served on the bridge's port (services/bridge/lib static_files.hpp): the page and its script
// with their types, nothing outside the root, a clear answer when the view was not built.
#include <fstream>

#include <gtest/gtest.h>

#include "twinslam/bridge/static_files.hpp"

namespace twinslam::bridge {
namespace {

namespace fs = std::filesystem;

struct WebRoot : ::testing::Test {
  fs::path dir = fs::temp_directory_path() / ("twinslam_web_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
                                              ::testing::UnitTest::GetInstance()->current_test_info()->name());
  void SetUp() override { fs::create_directories(dir / "sub"); }
  void TearDown() override { fs::remove_all(dir); }
  void write(const fs::path& file, const std::string& text) { std::ofstream(dir / file, std::ios::binary) << text; }
};

TEST_F(WebRoot, ThePageAndItsScriptAreServedWithTheirTypes) {
  write("index.html", "<html></html>");
  write("app.js", "console.log(1)");
  write("sub/x.css", "body{}");
  const StaticReply page = serve_static(dir, "GET", "/?ws=ws://h:1");
  EXPECT_EQ(page.status, 200u);
  EXPECT_EQ(page.body, "<html></html>");
  EXPECT_EQ(page.content_type, "text/html; charset=utf-8");
  EXPECT_EQ(serve_static(dir, "GET", "/app.js").content_type, "text/javascript; charset=utf-8");
  EXPECT_EQ(serve_static(dir, "HEAD", "/sub/x.css").body, "body{}");  // the caller sends only its length
  EXPECT_EQ(serve_static(dir, "GET", "/missing.js").status, 404u);
  EXPECT_EQ(serve_static(dir, "GET", "/sub").status, 404u);  // no directory listing
  EXPECT_EQ(serve_static(dir, "POST", "/").status, 405u);
}

TEST_F(WebRoot, NothingOutsideTheRootIsServed) {
  write("index.html", "x");
  std::ofstream(dir.parent_path() / "twinslam_web_secret.txt") << "secret";
  for (const char* target : {"/../twinslam_web_secret.txt", "/sub/../../twinslam_web_secret.txt", "/..", "/a\\b",
                             "relative", ""}) {
    const StaticReply r = serve_static(dir, "GET", target);
    EXPECT_EQ(r.status, 400u) << target;
    EXPECT_EQ(r.body.find("secret"), std::string::npos) << target;
  }
  EXPECT_EQ(serve_static(dir, "GET", std::string_view("/index.html\0x", 13)).status, 400u);
  fs::remove(dir.parent_path() / "twinslam_web_secret.txt");
}

TEST_F(WebRoot, AViewThatWasNotBuiltIsNamedInTheAnswer) {
  const StaticReply r = serve_static(dir, "GET", "/");
  EXPECT_EQ(r.status, 404u);
  EXPECT_NE(r.body.find("web view not built"), std::string::npos) << r.body;
  EXPECT_NE(r.body.find((dir / "index.html").string()), std::string::npos) << r.body;
}

}  // namespace
}  // namespace twinslam::bridge
