// The progress lines of long commands (run, bench, sim, twin build) as a log or a pipe sees them.
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "twinslam/core/progress.hpp"

namespace twinslam {
namespace {

// Everything written to a temporary stream, one entry per line.
std::vector<std::string> lines_of(std::FILE* f) {
  std::rewind(f);
  std::vector<std::string> lines;
  std::string line;
  for (int c = std::fgetc(f); c != EOF; c = std::fgetc(f)) {
    if (c == '\n') {
      lines.push_back(line);
      line.clear();
    } else {
      line += static_cast<char>(c);
    }
  }
  if (!line.empty()) lines.push_back(line);
  return lines;
}

TEST(Progress, PlainOutputIsOneLinePerTenPercentAndAFinalLine) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  Progress p("run", 200, true, f);
  p.set_plain();
  for (std::size_t k = 0; k <= 200; ++k) p.update(k);
  const auto lines = lines_of(f);
  ASSERT_EQ(lines.size(), 11u);  // 0 %, 10 %, ... 90 %, 100 %
  EXPECT_NE(lines.front().find("  0% 0/200"), std::string::npos) << lines.front();
  EXPECT_NE(lines[5].find(" 50% 100/200"), std::string::npos) << lines[5];
  EXPECT_NE(lines.back().find("100% 200/200"), std::string::npos) << lines.back();
  EXPECT_NE(lines.back().find("ETA"), std::string::npos);
  EXPECT_EQ(lines.back().rfind("run", 0), 0u);  // the label starts each line
  p.update(200);  // nothing after the end
  EXPECT_EQ(lines_of(f).size(), 11u);
  std::fclose(f);
}

TEST(Progress, WorkThatStopsShortEndsWithWhereItStopped) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  Progress p("bench vio", 1000, true, f);
  p.set_plain();
  p.update(370);
  p.finish(371);
  const auto lines = lines_of(f);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_NE(lines.back().find(" 37% 371/1000"), std::string::npos) << lines.back();
  std::fclose(f);
}

TEST(Progress, DisabledOrEmptyWorkPrintsNothing) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  Progress off("run", 10, false, f), empty("run", 0, true, f);
  off.set_plain();
  empty.set_plain();
  for (std::size_t k = 0; k <= 10; ++k) off.update(k);
  empty.update(0);
  empty.finish(0);
  EXPECT_TRUE(lines_of(f).empty());
  std::fclose(f);
}

TEST(Progress, CountsBeyondTheTotalAreClamped) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  Progress p("twin build", 4, true, f);
  p.set_plain();
  p.update(9);
  const auto lines = lines_of(f);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_NE(lines[0].find("100% 4/4"), std::string::npos) << lines[0];
  std::fclose(f);
}

}  // namespace
}  // namespace twinslam
