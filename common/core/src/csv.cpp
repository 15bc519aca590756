#include "twinslam/core/csv.hpp"

#include <charconv>
#include <cmath>
#include <fstream>

#include "twinslam/core/error.hpp"
#include "twinslam/core/text.hpp"

namespace twinslam {

std::string where(const std::string& file, std::size_t line, const std::string& what) {
  return line == 0 ? file + ": " + what : file + ":" + std::to_string(line) + ": " + what;
}

void read_csv(const std::filesystem::path& file, std::size_t columns,
              const std::function<void(const CsvRow&)>& on_row) {
  std::ifstream in(file);
  if (!in) throw InputError(where(file.string(), 0, "cannot open file"));
  std::string text;
  CsvRow row;
  while (std::getline(in, text)) {
    ++row.line;
    const std::string_view line = trim(text);
    if (line.empty() || line.front() == '#') continue;
    row.cells = split(line, ',');
    for (auto& c : row.cells) c = trim(c);
    if (columns == 0) columns = row.cells.size();
    if (row.cells.size() != columns) {
      throw InputError(where(file.string(), row.line,
                             "expected " + std::to_string(columns) + " columns, found " +
                                 std::to_string(row.cells.size())));
    }
    on_row(row);
  }
  if (in.bad()) throw InputError(where(file.string(), row.line, "read error"));
}

namespace {
[[noreturn]] void bad_cell(const std::filesystem::path& file, const CsvRow& row, std::size_t col,
                           std::string_view name, const std::string& why) {
  throw InputError(where(file.string(), row.line,
                         "column " + std::to_string(col + 1) + " (" + std::string(name) + "): " + why));
}
}  // namespace

std::int64_t parse_int64(const std::filesystem::path& file, const CsvRow& row, std::size_t col,
                         std::string_view name) {
  const std::string_view cell = row.cells.at(col);
  std::int64_t value = 0;
  const auto [ptr, ec] = std::from_chars(cell.data(), cell.data() + cell.size(), value);
  if (cell.empty() || ec != std::errc() || ptr != cell.data() + cell.size()) {
    bad_cell(file, row, col, name, "not an integer: '" + std::string(cell) + "'");
  }
  return value;
}

double parse_double(const std::filesystem::path& file, const CsvRow& row, std::size_t col, std::string_view name) {
  const std::string_view cell = row.cells.at(col);
  double value = 0.0;
  const auto [ptr, ec] = std::from_chars(cell.data(), cell.data() + cell.size(), value);
  if (cell.empty() || ec != std::errc() || ptr != cell.data() + cell.size()) {
    bad_cell(file, row, col, name, "not a number: '" + std::string(cell) + "'");
  }
  if (!std::isfinite(value)) bad_cell(file, row, col, name, "not finite: '" + std::string(cell) + "'");
  return value;
}

}  // namespace twinslam
