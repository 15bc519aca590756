#pragma once
// Private: the feature / batch tables of 3D Tiles 1.0 tile formats (a JSON header plus a binary body; a property is
// either a JSON array or {"byteOffset", "componentType", "type"} pointing into the binary body).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "twinslam/twin/b3dm.hpp"

namespace twinslam::twin::detail {

struct TableBytes {
  const std::uint8_t* json = nullptr;
  std::size_t json_size = 0;
  const std::uint8_t* binary = nullptr;
  std::size_t binary_size = 0;
};

// The JSON header as an object ({} when empty); trailing padding (spaces, NULs) is ignored. `what` names the table.
nlohmann::json parse_table_json(const TableBytes& t, const std::string& name, const std::string& what);

// A global or per-feature property as doubles: `count` elements of `components` values each. A JSON array must hold
// count * components numbers; a binary reference uses its componentType (default_type when it has none, as
// RTC_CENTER's FLOAT) and must lie inside the binary body, aligned to its component size.
std::vector<double> table_numbers(const TableBytes& t, const nlohmann::json& value, std::size_t count, int components,
                                  const std::string& default_type, const std::string& name, const std::string& what);

// The numeric SCALAR properties of a batch table (others skipped), each checked to hold batch_length values.
BatchTable parse_batch_table(const TableBytes& t, std::size_t batch_length, const std::string& name);

}  // namespace twinslam::twin::detail
