// Strict CSV parsing: every malformed row is reported with file and line, never skipped.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "twinslam/core/csv.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/core/text.hpp"
#include "scratch_dir.hpp"

namespace fs = std::filesystem;
using namespace twinslam;

namespace {
fs::path write_file(const std::string& name, const std::string& text) {
  const fs::path dir = twinslam::test::scratch_dir() / "csv";
  fs::create_directories(dir);
  std::ofstream(dir / name) << text;
  return dir / name;
}

std::string error_of(const fs::path& file, std::size_t columns) {
  try {
    read_csv(file, columns, [&](const CsvRow& row) {
      for (std::size_t c = 1; c < row.cells.size(); ++c) parse_double(file, row, c, "value");
      parse_int64(file, row, 0, "timestamp");
    });
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(Csv, ReadsRowsSkippingCommentsAndBlankLines) {
  const auto f = write_file("ok.csv", "#t,a,b\n1,2.5,-3e-2\n\n2,0,1\n");
  std::vector<std::int64_t> stamps;
  std::vector<double> values;
  read_csv(f, 3, [&](const CsvRow& row) {
    stamps.push_back(parse_int64(f, row, 0, "t"));
    values.push_back(parse_double(f, row, 2, "b"));
  });
  EXPECT_EQ(stamps, (std::vector<std::int64_t>{1, 2}));
  EXPECT_EQ(values, (std::vector<double>{-3e-2, 1.0}));
}

TEST(Csv, WrongColumnCountNamesFileAndLine) {
  const auto f = write_file("cols.csv", "#t,a,b\n1,2,3\n2,3\n");
  EXPECT_EQ(error_of(f, 3), f.string() + ":3: expected 3 columns, found 2");
}

TEST(Csv, NonNumericAndNanCellsNameTheColumn) {
  const auto f = write_file("nan.csv", "1,2,abc\n");
  EXPECT_EQ(error_of(f, 3), f.string() + ":1: column 3 (value): not a number: 'abc'");
  const auto g = write_file("nan2.csv", "1,nan,2\n");
  EXPECT_EQ(error_of(g, 3), g.string() + ":1: column 2 (value): not finite: 'nan'");
  const auto h = write_file("ts.csv", "1.5,1,2\n");
  EXPECT_EQ(error_of(h, 3), h.string() + ":1: column 1 (timestamp): not an integer: '1.5'");
}

TEST(Csv, MissingFileIsAnInputError) {
  EXPECT_EQ(error_of("/nonexistent/x.csv", 0), "/nonexistent/x.csv: cannot open file");
}

TEST(Text, ExpandsEnvironmentWithDefaults) {
  ::setenv("TWINSLAM_TEST_VAR", "abc", 1);
  EXPECT_EQ(expand_env("x${TWINSLAM_TEST_VAR}y"), "xabcy");
  EXPECT_EQ(expand_env("${TWINSLAM_TEST_UNSET_VAR:-dflt}/z"), "dflt/z");
  EXPECT_EQ(expand_env("${TWINSLAM_TEST_UNSET_VAR}"), "");
  EXPECT_EQ(expand_env("no vars $ here"), "no vars $ here");
}
