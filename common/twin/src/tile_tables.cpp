// Feature / batch table parsing (3D Tiles 1.0, "Feature Table" and "Batch Table" specifications).
#include "tile_tables.hpp"

#include <cmath>
#include <cstring>

#include "twinslam/core/error.hpp"

namespace twinslam::twin::detail {
namespace {

// Bytes per component of a table componentType; 0 if unknown.
int component_size(const std::string& type) {
  if (type == "BYTE" || type == "UNSIGNED_BYTE") return 1;
  if (type == "SHORT" || type == "UNSIGNED_SHORT") return 2;
  if (type == "INT" || type == "UNSIGNED_INT" || type == "FLOAT") return 4;
  if (type == "DOUBLE") return 8;
  return 0;
}

double read_component(const std::uint8_t* p, const std::string& type) {
  auto get = [p](auto v) { std::memcpy(&v, p, sizeof(v)); return static_cast<double>(v); };
  if (type == "BYTE") return get(std::int8_t{});
  if (type == "UNSIGNED_BYTE") return get(std::uint8_t{});
  if (type == "SHORT") return get(std::int16_t{});
  if (type == "UNSIGNED_SHORT") return get(std::uint16_t{});
  if (type == "INT") return get(std::int32_t{});
  if (type == "UNSIGNED_INT") return get(std::uint32_t{});
  if (type == "FLOAT") return get(float{});
  return get(double{});
}

int type_components(const std::string& type) {
  if (type == "SCALAR") return 1;
  if (type == "VEC2") return 2;
  if (type == "VEC3") return 3;
  if (type == "VEC4") return 4;
  return 0;
}

}  // namespace

nlohmann::json parse_table_json(const TableBytes& t, const std::string& name, const std::string& what) {
  std::size_t n = t.json_size;
  while (n > 0 && (t.json[n - 1] == ' ' || t.json[n - 1] == '\0')) --n;
  if (n == 0) return nlohmann::json::object();
  nlohmann::json j = nlohmann::json::parse(t.json, t.json + n, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded()) throw InputError(where(name, 0, what + " JSON is malformed"));
  if (!j.is_object()) throw InputError(where(name, 0, what + " JSON is not an object"));
  return j;
}

std::vector<double> table_numbers(const TableBytes& t, const nlohmann::json& value, std::size_t count, int components,
                                  const std::string& default_type, const std::string& name, const std::string& what) {
  const std::size_t total = count * static_cast<std::size_t>(components);
  std::vector<double> out;
  if (value.is_array()) {
    // Per-feature JSON values may be nested ([[x, y, z], ...]): flatten one level.
    for (const auto& v : value) {
      if (v.is_array()) {
        for (const auto& w : v) {
          if (!w.is_number()) throw InputError(where(name, 0, what + " holds a non-number"));
          out.push_back(w.get<double>());
        }
      } else if (v.is_number()) {
        out.push_back(v.get<double>());
      } else {
        throw InputError(where(name, 0, what + " holds a non-number"));
      }
    }
    if (out.size() != total) {
      throw InputError(where(name, 0, what + " has " + std::to_string(out.size()) + " values, expected " +
                                          std::to_string(total)));
    }
    return out;
  }
  if (!value.is_object() || !value.contains("byteOffset") || !value["byteOffset"].is_number_unsigned()) {
    throw InputError(where(name, 0, what + " is neither an array nor a binary reference with byteOffset"));
  }
  const std::string ctype = value.contains("componentType") && value["componentType"].is_string()
                                ? value["componentType"].get<std::string>() : default_type;
  const int csize = component_size(ctype);
  if (csize == 0) throw InputError(where(name, 0, what + " has unknown componentType '" + ctype + "'"));
  const std::size_t offset = value["byteOffset"].get<std::size_t>();
  if (offset % static_cast<std::size_t>(csize) != 0) {
    throw InputError(where(name, 0, what + " byteOffset " + std::to_string(offset) + " not aligned to its " +
                                        std::to_string(csize) + "-byte components"));
  }
  const std::size_t bytes = total * static_cast<std::size_t>(csize);
  if (offset > t.binary_size || bytes > t.binary_size - offset) {
    throw InputError(where(name, 0, what + " (" + std::to_string(bytes) + " bytes at " + std::to_string(offset) +
                                        ") runs past the binary body of " + std::to_string(t.binary_size) + " bytes"));
  }
  out.resize(total);
  for (std::size_t i = 0; i < total; ++i) {
    out[i] = read_component(t.binary + offset + i * static_cast<std::size_t>(csize), ctype);
  }
  return out;
}

BatchTable parse_batch_table(const TableBytes& t, std::size_t batch_length, const std::string& name) {
  BatchTable table;
  table.batch_length = batch_length;
  const nlohmann::json j = parse_table_json(t, name, "batch table");
  for (const auto& [key, value] : j.items()) {
    if (key == "extensions" || key == "extras") continue;
    const std::string what = "batch table property '" + key + "'";
    if (value.is_array()) {
      if (value.size() != batch_length) {
        throw InputError(where(name, 0, what + " has " + std::to_string(value.size()) + " values, BATCH_LENGTH is " +
                                            std::to_string(batch_length)));
      }
      bool numeric = true;
      for (const auto& v : value) numeric = numeric && v.is_number();
      if (numeric) table.numbers[key] = table_numbers(t, value, batch_length, 1, "", name, what);
    } else if (value.is_object() && value.contains("byteOffset")) {
      const std::string type =
          value.contains("type") && value["type"].is_string() ? value["type"].get<std::string>() : std::string();
      if (type_components(type) == 0) throw InputError(where(name, 0, what + " has unknown type '" + type + "'"));
      if (type == "SCALAR") table.numbers[key] = table_numbers(t, value, batch_length, 1, "", name, what);
      else table_numbers(t, value, batch_length, type_components(type), "", name, what);  // checked, not kept
    }
  }
  return table;
}

}  // namespace twinslam::twin::detail
