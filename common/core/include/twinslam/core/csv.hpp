#pragma once
// Strict CSV reading for sensor files (EuRoC ASL and friends). Every malformed row is an InputError that names the
// file and line: a robotics log with a silently skipped row is a log with a hidden gap.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace twinslam {

struct CsvRow {
  std::size_t line = 0;                 // 1-based line number in the file
  std::vector<std::string_view> cells;  // trimmed; valid only during the callback
};

// Calls on_row for every data row. Lines starting with '#' and blank lines are skipped (EuRoC headers start with '#').
// Throws InputError if the file cannot be opened or a row has a different number of cells than `columns`
// (0 = take the count from the first data row).
void read_csv(const std::filesystem::path& file, std::size_t columns,
              const std::function<void(const CsvRow&)>& on_row);

// Cell parsers: exact, whole-cell conversions (std::from_chars), finite values only.
// They throw InputError "FILE:LINE: column N (<name>): <reason>".
std::int64_t parse_int64(const std::filesystem::path& file, const CsvRow& row, std::size_t col, std::string_view name);
double parse_double(const std::filesystem::path& file, const CsvRow& row, std::size_t col, std::string_view name);

}  // namespace twinslam
