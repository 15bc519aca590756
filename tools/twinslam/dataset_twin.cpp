#include "dataset_twin.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "twinslam/core/error.hpp"
#include "twinslam/core/progress.hpp"
#include "twinslam/twin/load.hpp"
#include "twinslam/twin/store.hpp"

namespace twinslam::cli {
namespace fs = std::filesystem;
namespace {

// FNV-1a 64: a content key for the cache, not security.
struct Fnv {
  std::uint64_t h = 1469598103934665603ull;
  void add(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ull;
  }
  void add(const std::string& s) { add(s.data(), s.size()); }
};

std::vector<fs::path> twin_files(const fs::path& p) {
  std::vector<fs::path> files;
  if (fs::is_regular_file(p)) return {p};
  for (const auto& e : fs::recursive_directory_iterator(p)) {
    if (e.is_regular_file()) files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::string content_hash(const DatasetGeo& geo, const twin::StoreConfig& store) {
  Fnv f;
  f.add(origin_text(geo.origin) + "|" + geo.crs.value_or("W") + "|" + std::to_string(store.tile_size_m) + "|" +
        std::to_string(store.point_spacing_m));
  for (const auto& file : twin_files(geo.twin_path)) {
    f.add(fs::relative(file, geo.twin_path.parent_path()).string());
    std::ifstream in(file, std::ios::binary);
    const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    f.add(bytes.data(), bytes.size());
  }
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(f.h));
  return buf;
}

fs::path cache_root() {
  if (const char* c = std::getenv("TWINSLAM_CACHE"); c != nullptr && *c != '\0') return c;
  if (const char* h = std::getenv("HOME"); h != nullptr && *h != '\0') return fs::path(h) / ".cache/twinslam";
  return fs::temp_directory_path() / "twinslam-cache";
}

}  // namespace

std::string origin_text(const twin::GeoOrigin& o) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%.9f,%.9f,%.4f", o.lat_deg, o.lon_deg, o.alt_m);
  return buf;
}

DatasetGeo read_dataset_geo(const fs::path& root) {
  const std::string file = (root / "dataset.yaml").string();
  YAML::Node y;
  try {
    y = YAML::LoadFile(file);
  } catch (const YAML::BadFile&) {
    throw InputError(where(file, 0, "missing: twin modes need the dataset's origin and twin"));
  } catch (const YAML::Exception& e) {
    throw InputError(where(file, static_cast<std::size_t>(e.mark.line + 1), "malformed YAML: " + e.msg));
  }
  DatasetGeo geo;
  try {
    const YAML::Node o = y["origin"];
    if (!o || !o["lat"] || !o["lon"] || !o["alt"]) throw InputError(where(file, 0, "key 'origin' needs lat, lon, alt"));
    geo.origin = {o["lat"].as<double>(), o["lon"].as<double>(), o["alt"].as<double>()};
    const YAML::Node t = y["twin"];
    if (!t || !t["path"]) throw InputError(where(file, 0, "key 'twin.path' is missing"));
    geo.twin_path = root / t["path"].as<std::string>();
    const std::string crs = t["crs"] ? t["crs"].as<std::string>() : "ENU@origin";
    if (crs != "ENU@origin") geo.crs = crs;
  } catch (const YAML::Exception& e) {
    throw InputError(where(file, static_cast<std::size_t>(e.mark.line + 1), "bad origin or twin: " + e.msg));
  }
  if (!fs::exists(geo.twin_path)) throw InputError(where(file, 0, "twin '" + geo.twin_path.string() + "' does not exist"));
  return geo;
}

twin::Mesh load_dataset_twin(const DatasetGeo& geo) {
  twin::LoadOptions load;
  load.origin = geo.origin;
  load.crs = geo.crs;
  // A folder: its 3D Tiles tileset.json (which pulls in its content), else each file at its top level.
  std::vector<fs::path> sources;
  if (fs::is_directory(geo.twin_path)) {
    if (fs::exists(geo.twin_path / "tileset.json")) {
      sources = {geo.twin_path / "tileset.json"};
    } else {
      for (const auto& e : fs::directory_iterator(geo.twin_path)) {
        if (e.is_regular_file()) sources.push_back(e.path());
      }
      std::sort(sources.begin(), sources.end());
    }
  } else {
    sources = {geo.twin_path};
  }
  twin::Mesh mesh_W;
  for (const auto& file : sources) mesh_W.append(twin::load_twin_source(file.string(), load));
  return mesh_W;
}

fs::path dataset_twin_store(const DatasetGeo& geo, bool quiet) {
  const twin::StoreConfig store;
  const fs::path dir = cache_root() / "twins" / content_hash(geo, store);
  if (fs::exists(dir / "index.json")) {
    if (!quiet) std::printf("twin: reusing store %s\n", dir.string().c_str());
    return dir;
  }
  const twin::Mesh mesh_W = load_dataset_twin(geo);
  fs::create_directories(dir.parent_path());
  // Per process: two runs of the same dataset may build it at once (parallel benches, ctest).
  const fs::path tmp = dir.string() + ".tmp" + std::to_string(::getpid());
  fs::remove_all(tmp);
  std::optional<Progress> bar;  // created at the first call, when the number of tiles is known
  twin::build_twin_store(mesh_W, geo.origin, store, tmp.string(), [&](std::size_t done, std::size_t n) {
    if (!bar) bar.emplace("twin store", n, !quiet);
    bar->update(done);
  });
  std::error_code renamed;
  fs::rename(tmp, dir, renamed);  // whole store or nothing: a run killed mid-build leaves no half store under the key
  if (renamed) {
    fs::remove_all(tmp);
    // Another process finished the same store first: same content hash, same store.
    if (!fs::exists(dir / "index.json")) throw InputError(where(dir.string(), 0, "cannot store the twin: " + renamed.message()));
  }
  if (!quiet) std::printf("twin: built store %s (%s)\n", dir.string().c_str(), geo.twin_path.string().c_str());
  return dir;
}

}  // namespace twinslam::cli
