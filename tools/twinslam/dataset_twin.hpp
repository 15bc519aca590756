#pragma once
// The digital twin of a dataset for `twinslam run` in twin modes: DIR/dataset.yaml names W's origin and the twin
// (CONTRACTS.md, dataset layout); the twin is built into a tiled store once and reused, keyed by the content hash of
// the twin files, the origin and the store settings (so an edited twin is rebuilt, an unchanged one is not).
#include <filesystem>
#include <optional>
#include <string>

#include "twinslam/twin/geo.hpp"
#include "twinslam/twin/mesh.hpp"

namespace twinslam::cli {

struct DatasetGeo {
  twin::GeoOrigin origin;
  std::filesystem::path twin_path;  // file or folder, absolute
  std::optional<std::string> crs;   // of the twin's coordinates when the file does not say; nullopt: already W
};

// From DIR/dataset.yaml; InputError naming the file and key when it is missing or malformed.
DatasetGeo read_dataset_geo(const std::filesystem::path& dataset_root);

// The dataset's twin in W, every source loaded and appended (a folder: its tileset.json, else each file in it).
// InputError on a bad twin.
twin::Mesh load_dataset_twin(const DatasetGeo& geo);

// The store folder for the dataset's twin, built now if no store with the same hash exists under the cache
// ($TWINSLAM_CACHE, else $HOME/.cache/twinslam). Prints one line saying which. InputError on a bad twin.
std::filesystem::path dataset_twin_store(const DatasetGeo& geo, bool quiet);

// "LAT,LON,ALT" of an origin, for a service's --origin option.
std::string origin_text(const twin::GeoOrigin& origin);

}  // namespace twinslam::cli
