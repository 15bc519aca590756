// The quirk table: what each quirk is and what the loader does about it (the CesiumJS fallback).
#include "tiles3d_quirks.hpp"

#include <algorithm>

#include "twinslam/core/error.hpp"

namespace twinslam::twin::detail {
namespace {

struct QuirkText {
  const char* what;
  const char* fallback;
};

QuirkText text(Quirk q) {
  switch (q) {
    case Quirk::kNoAssetVersion: return {"tileset without asset.version", "read as 1.0"};
    case Quirk::kPreReleaseVersion: return {"asset.version 0.0 (pre-1.0)", "read as 1.0"};
    case Quirk::kNoRootRefine: return {"root tile without refine", "REPLACE assumed"};
    case Quirk::kNoGeometricError:
      return {"tile without geometricError", "the parent's value used (the root: the tileset's)"};
    case Quirk::kContentUrl: return {"content.url (pre-1.0) instead of content.uri", "url used"};
    case Quirk::kLegacyB3dmHeader: return {"legacy b3dm header (20 / 24 bytes)", "read with the legacy layout"};
    case Quirk::kUnpaddedB3dm: return {"b3dm byteLength not a multiple of 8", "unpadded tail ignored"};
    case Quirk::kCesiumRtc: return {"glTF CESIUM_RTC extension (deprecated)", "its center added"};
  }
  return {"unknown quirk", "accepted"};
}

}  // namespace

void note_quirk(Quirk quirk, const std::string& file, const std::string& at, bool strict, LoadReport* report) {
  const QuirkText t = text(quirk);
  if (strict) throw QuirkRefused(where(file, 0, at + ": " + t.what + " (refused in strict mode)"));
  if (report == nullptr) return;
  const std::string key = file + ": " + t.what + " ";
  const bool listed = std::any_of(report->warnings.begin(), report->warnings.end(),
                                  [&](const std::string& line) { return line.rfind(key, 0) == 0; });
  if (!listed) report->warnings.push_back(key + "(first at " + at + "); " + t.fallback);
}

}  // namespace twinslam::twin::detail
