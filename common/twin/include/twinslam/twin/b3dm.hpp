#pragma once
// OGC 3D Tiles Batched 3D Model (b3dm) tiles: header, feature table (BATCH_LENGTH, RTC_CENTER), batch table
// (per-feature properties), embedded binary glTF. Headers accepted as CesiumJS does:
//   current (28 bytes): featureTableJSON, featureTableBinary, batchTableJSON, batchTableBinary byte lengths
//   legacy 1 (20 bytes): batchLength, batchTableByteLength
//   legacy 2 (24 bytes): batchTableJSONByteLength, batchTableBinaryByteLength, batchLength
// A legacy header is recognized when the word read as batchTableJSONByteLength (legacy 1) or
// batchTableBinaryByteLength (legacy 2) is >= 0x22000000: it is then really the start of the JSON ('"' / '{') or of
// the glTF magic, and no real table is 570 MB long.
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "twinslam/twin/gltf.hpp"

namespace twinslam::twin {

// The batch table's numeric scalar properties (JSON arrays or binary SCALAR references), one value per batch id.
// Other properties (strings, vectors, nested objects) are not kept.
struct BatchTable {
  std::size_t batch_length = 0;
  std::map<std::string, std::vector<double>> numbers;
  const std::vector<double>* find(const std::string& key) const {
    auto it = numbers.find(key);
    return it == numbers.end() ? nullptr : &it->second;
  }
};

struct B3dmContent {
  GltfContent gltf;                             // mesh in the glTF y-up model frame + per-vertex batch ids
  std::optional<Eigen::Vector3d> rtc_center;    // feature table RTC_CENTER, z-up tile frame [m]
  BatchTable batch_table;
  int header_bytes = 28;                        // 20 / 24 for the legacy headers
  bool unpadded = false;                        // byteLength not a multiple of 8 (accepted by kLenient only)
};

// kStrict also requires the spec's 8-byte padding of the whole tile (byteLength % 8 == 0), as 3d-tiles-validator
// does. kLenient (what the tileset loader uses, like CesiumJS) tolerates an unpadded tail: the 2017 sample
// generator wrote such tiles (e.g. 3d-tiles-samples TilesetWithRequestVolume city/ll.b3dm) and the tail holds no
// data. Both modes require the inner sections (feature / batch tables, glb) to start on 8-byte boundaries.
enum class B3dmCheck { kLenient, kStrict };

// Throws InputError naming `name` and the problem (bad magic / version, lengths past the end, misaligned sections,
// malformed table JSON, bad glb, batch ids >= BATCH_LENGTH ...).
B3dmContent parse_b3dm(const std::uint8_t* data, std::size_t size, const std::string& name,
                       B3dmCheck check = B3dmCheck::kLenient);
B3dmContent load_b3dm_file(const std::string& path, B3dmCheck check = B3dmCheck::kLenient);

}  // namespace twinslam::twin
