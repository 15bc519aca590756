// `twinslam twin build SRC... --origin LAT,LON,ALT [--crs EPSG:nnnn] --out TWIN_DIR` and `twinslam twin info TWIN_DIR
// [--json] [--preview PNG]` (CONTRACTS.md): load twin sources into one mesh in W, cut it into the tiled Draco store,
// and describe a store.
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "twin_preview.hpp"
#include "twinslam/core/error.hpp"
#include "twinslam/core/main_guard.hpp"
#include "twinslam/twin/load.hpp"
#include "twinslam/core/progress.hpp"
#include "twinslam/twin/store.hpp"

namespace twinslam::cli {
namespace {

struct BuildOptions {
  std::vector<std::string> sources;
  std::string origin, out;
  std::optional<std::string> crs;
  twin::StoreConfig store;
  double max_geometric_error_m = 0.0;
  bool strict = false;
};

struct InfoOptions {
  std::string dir, preview;
  bool json = false;
};

std::string box_text(const Eigen::AlignedBox3d& b) {
  char buf[200];
  std::snprintf(buf, sizeof buf, "e %.2f .. %.2f, n %.2f .. %.2f, u %.2f .. %.2f m", b.min().x(), b.max().x(),
                b.min().y(), b.max().y(), b.min().z(), b.max().z());
  return buf;
}

int run_build(const BuildOptions& o) {
  const twin::GeoOrigin origin = twin::parse_origin(o.origin);
  o.store.validate();  // before loading: a typo in --tile-size should not wait for a large source to load
  if (!(o.max_geometric_error_m >= 0.0)) throw UsageError("--max-geometric-error must be >= 0 m");
  twin::LoadOptions load;
  load.origin = origin;
  load.crs = o.crs;
  load.max_geometric_error_m = o.max_geometric_error_m;
  load.strict = o.strict;
  twin::Mesh mesh_W;
  bool have_points = false, have_triangles = false;
  for (const std::string& src : o.sources) {
    twin::LoadReport report;
    const twin::Mesh part = twin::load_twin_source(src, load, &report);
    const bool points = part.triangles.empty() && !part.p_W.empty();
    // Mesh::append would keep a point set's points only as unreferenced vertices of a triangle mesh: refuse instead.
    if ((points && have_triangles) || (!points && !part.empty() && have_points)) {
      throw UsageError(src + ": cannot combine point-set and triangle-mesh sources in one twin");
    }
    have_points |= points;
    have_triangles |= !points && !part.empty();
    std::printf("source %s: %zu triangles, %zu %s, %zu parts, %zu rejected, %zu warnings\n", src.c_str(),
                part.num_triangles(), part.num_vertices(), points ? "points" : "vertices", report.parts_loaded,
                report.rejected.size(), report.warnings.size());
    for (const std::string& why : report.rejected) std::printf("  rejected %s\n", why.c_str());
    for (const std::string& quirk : report.warnings) std::printf("  warning %s\n", quirk.c_str());
    mesh_W.append(part);
  }
  if (mesh_W.empty()) throw InputError(where(o.sources.front(), 0, "the sources hold no geometry"));
  std::optional<Progress> bar;  // created at the first call, when the number of tiles is known
  const twin::TwinIndex index = twin::build_twin_store(mesh_W, origin, o.store, o.out, [&](std::size_t done, std::size_t n) {
    if (!bar) bar.emplace("twin build", n, true);
    bar->update(done);
  });
  std::size_t bytes = 0;
  for (const twin::TileInfo& t : index.tiles) bytes += t.bytes;
  std::printf("twin %s: id %s, %zu tiles of %.0f m, %zu triangles, %zu points (spacing %.2f m), %.1f MB; %s\n",
              o.out.c_str(), index.twin_id.c_str(), index.tiles.size(), index.tile_size_m, index.triangles,
              index.points, index.point_spacing_m, bytes / 1e6, box_text(index.extent_W).c_str());
  return kExitOk;
}

int run_info(const InfoOptions& o) {
  const twin::TwinIndex index = twin::read_twin_index(o.dir);
  std::size_t bytes = 0;
  for (const twin::TileInfo& t : index.tiles) bytes += t.bytes;
  std::optional<std::pair<int, int>> preview_size;
  if (!o.preview.empty()) preview_size = write_twin_preview(o.dir, index, o.preview);
  const Eigen::AlignedBox3d& b = index.extent_W;
  if (o.json) {
    const nlohmann::json j = {
        {"origin", {index.origin.lat_deg, index.origin.lon_deg, index.origin.alt_m}},
        {"tiles", index.tiles.size()},
        {"triangles", index.triangles},
        {"points", index.points},
        {"extent_enu", {b.min().x(), b.min().y(), b.min().z(), b.max().x(), b.max().y(), b.max().z()}},
        {"twin_id", index.twin_id},
        {"tile_size_m", index.tile_size_m},
        {"point_spacing_m", index.point_spacing_m},
        {"bytes", bytes}};
    std::cout << j.dump() << std::endl;  // one object, one line: scripts parse stdout
    return kExitOk;
  }
  std::printf("twin %s: id %s, origin %.7f, %.7f, %.3f m\n", o.dir.c_str(), index.twin_id.c_str(), index.origin.lat_deg,
              index.origin.lon_deg, index.origin.alt_m);
  std::printf("extent %s\n", box_text(b).c_str());
  std::printf("tiles %zu of %.0f m, triangles %zu, points %zu (spacing %.2f m), %.1f MB\n", index.tiles.size(),
              index.tile_size_m, index.triangles, index.points, index.point_spacing_m, bytes / 1e6);
  if (preview_size)
    std::printf("preview %s (%d x %d px)\n", o.preview.c_str(), preview_size->first, preview_size->second);
  return kExitOk;
}

}  // namespace

void add_twin_command(CLI::App& app, int& exit_code) {
  CLI::App* twin = app.add_subcommand("twin", "Digital twin: build the tiled store from sources, describe a store");
  twin->require_subcommand(1);
  add_twin_changes_command(*twin, exit_code);

  auto b = std::make_shared<BuildOptions>();
  CLI::App* build = twin->add_subcommand(
      "build",
      "Load twin sources (PLY, OBJ, glTF/GLB, 3D Tiles tileset.json, CityJSON, OSM XML) into W and write the "
      "tiled, Draco-compressed store");
  build->add_option("SRC", b->sources, "Source files (appended into one twin)")->required()->type_name("SRC...");
  build->add_option("--origin", b->origin, "Origin of W: WGS84 latitude, longitude [deg], ellipsoidal height [m]")
      ->required()
      ->type_name("LAT,LON,ALT");
  build->add_option("--crs", b->crs, "CRS of source coordinates when the file does not say (e.g. EPSG:2056)")
      ->type_name("EPSG:nnnn");
  build->add_option("--out", b->out, "Twin folder to write (index.json + tiles/)")->required()->type_name("TWIN_DIR");
  build->add_option("--tile-size", b->store.tile_size_m, "Side of a square tile [m]")->capture_default_str();
  build->add_option("--spacing", b->store.point_spacing_m, "Mean spacing of the sampled points [m]")
      ->capture_default_str();
  build->add_option("--position-bits", b->store.position_bits, "Draco position quantization [bits]")
      ->capture_default_str();
  build->add_option("--seed", b->store.seed, "Seed of the point sampling")->capture_default_str();
  build
      ->add_option("--max-geometric-error", b->max_geometric_error_m,
                   "3D Tiles: use the finest level whose geometricError is >= M (0 = leaves) [m]")
      ->type_name("M")
      ->capture_default_str();
  build->add_flag("--strict", b->strict,
                  "3D Tiles: refuse what CesiumJS accepts with a warning (missing geometricError or asset.version, "
                  "content.url, legacy or unpadded b3dm, CESIUM_RTC)");
  build->callback([b, &exit_code] { exit_code = run_build(*b); });

  auto i = std::make_shared<InfoOptions>();
  CLI::App* info = twin->add_subcommand("info", "Extent, tiles, triangles and points of a twin store");
  info->add_option("TWIN_DIR", i->dir, "Twin folder (with index.json)")->required();
  info->add_flag("--json", i->json, "Print one JSON object (origin, tiles, triangles, points, extent_enu, ...)");
  info->add_option("--preview", i->preview, "Write a top-down PNG of the tiles (height-coloured, tile grid)")
      ->type_name("PNG");
  info->callback([i, &exit_code] { exit_code = run_info(*i); });
}

}  // namespace twinslam::cli
