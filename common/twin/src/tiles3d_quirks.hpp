#pragma once
// Real-world 3D Tiles quirks: what pre-1.0 and non-conforming exporters write and CesiumJS still loads, with a
// warning. The tileset loader accepts each with the same fallback as CesiumJS and one warning line per quirk and
// file in LoadReport::warnings; in strict mode (LoadOptions::strict, `twin build --strict`) each is an InputError, as
// the 3D Tiles spec and 3d-tiles-validator have it.
#include <string>

#include "twinslam/core/error.hpp"
#include "twinslam/twin/load.hpp"

namespace twinslam::twin::detail {

enum class Quirk {
  kNoAssetVersion,     // tileset without asset.version: read as 1.0
  kPreReleaseVersion,  // asset.version "0.0" (pre-1.0 exporters): read as 1.0
  kNoRootRefine,       // root tile without refine: REPLACE
  kNoGeometricError,   // tile without geometricError: its parent's value (root: the tileset's)
  kContentUrl,         // content.url (pre-1.0) instead of content.uri
  kLegacyB3dmHeader,   // b3dm with the 20 / 24-byte header of 2016 exporters
  kUnpaddedB3dm,       // b3dm byteLength not a multiple of 8 (the tail holds no data)
  kCesiumRtc,          // glTF CESIUM_RTC extension (deprecated; RTC_CENTER in the feature table replaces it)
};

// A quirk refused in strict mode: ends the whole load (the loaders let it through where they collect other bad
// parts as rejected), so `twin build --strict` exits 2 naming it.
class QuirkRefused : public InputError {
 public:
  using InputError::InputError;
};

// strict: throws QuirkRefused "<file>: <at>: <quirk> (refused in strict mode)". Otherwise adds
// "<file>: <quirk> (first at <at>); <fallback>" to report->warnings unless that file already has that quirk listed.
void note_quirk(Quirk quirk, const std::string& file, const std::string& at, bool strict, LoadReport* report);

}  // namespace twinslam::twin::detail
