// CrsTransform: source CRS -> WGS84 3D (EPSG:4979) through PROJ 9, one PJ_CONTEXT per object (PROJ contexts are not
// thread-safe; one per transform lets loaders run in parallel).
//
// Compound CRSs (projected + vertical, e.g. EPSG:7415 RD New + NAP height) without their geoid grid: measured with
// Debian's proj-data (no network, no nlgeo/rdtrans grids), proj_create_crs_to_crs(EPSG:7415, EPSG:4979) picks
// "Ballpark geographic offset + ballpark vertical transformation": horizontally ~110 m off at Amersfoort (it drops the
// Amersfoort->WGS84 datum shift) and vertically h = NAP height, ~43 m below the true ellipsoidal height. So when the
// best compound operation is a ballpark one we split deliberately:
//   horizontal: the horizontal sub-CRS -> EPSG:4979 (RD: "Amersfoort to WGS 84 (4)", ~1 m), height passed through;
//   vertical:   h = H + N_EGM96(lat, lon), the source's gravity-related height treated as EGM96 height
//               (egm96_15.gtx ships in proj-data). NAP vs EGM96 differ by < ~1-2 m in the Netherlands, which is
//               far better than the 43 m of the ballpark; if even the EGM96 grid is missing, h = H (ballpark) and
//               method() says so.
#include <proj.h>

#include <cmath>

#include "twinslam/core/error.hpp"
#include "twinslam/twin/geo.hpp"

namespace twinslam::twin {
namespace {

std::string proj_reason(PJ_CONTEXT* ctx) {
  const int err = proj_context_errno(ctx);
  const char* s = err != 0 ? proj_context_errno_string(ctx, err) : nullptr;
  // PROJ 9.1 reports an unknown EPSG code only as "Unknown error (code 4096)": say what it means.
  if (s == nullptr || std::string(s).rfind("Unknown error", 0) == 0)
    return "not in PROJ's database (proj.db) nor a valid CRS definition";
  return s;
}

// Whether the best operation PROJ can run here (available grids only) uses a ballpark step.
bool best_operation_is_ballpark(PJ_CONTEXT* ctx, PJ* src, PJ* dst) {
  PJ_OPERATION_FACTORY_CONTEXT* factory = proj_create_operation_factory_context(ctx, nullptr);
  if (factory == nullptr) return false;
  proj_operation_factory_context_set_grid_availability_use(ctx, factory,
                                                           PROJ_GRID_AVAILABILITY_DISCARD_OPERATION_IF_MISSING_GRID);
  proj_operation_factory_context_set_spatial_criterion(ctx, factory, PROJ_SPATIAL_CRITERION_PARTIAL_INTERSECTION);
  PJ_OBJ_LIST* ops = proj_create_operations(ctx, src, dst, factory);
  bool ballpark = true;  // no operation at all counts as ballpark: nothing better is available
  if (ops != nullptr && proj_list_get_count(ops) > 0) {
    PJ* op = proj_list_get(ctx, ops, 0);
    ballpark = proj_coordoperation_has_ballpark_transformation(ctx, op) != 0;
    proj_destroy(op);
  }
  proj_list_destroy(ops);
  proj_operation_factory_context_destroy(factory);
  return ballpark;
}

}  // namespace

struct CrsTransform::Impl {
  PJ_CONTEXT* ctx = nullptr;
  PJ* op = nullptr;     // source (or its horizontal part) -> 4979, normalized axis order
  PJ* geoid = nullptr;  // split mode only: (lon, lat, EGM96 height) -> (lon, lat, h)
  std::string method;
  ~Impl() {
    proj_destroy(geoid);
    proj_destroy(op);
    proj_context_destroy(ctx);
  }
  PJ* normalized_op(PJ* src, const char* dst_def) {
    PJ* dst = proj_create(ctx, dst_def);
    PJ* raw = dst != nullptr ? proj_create_crs_to_crs_from_pj(ctx, src, dst, nullptr, nullptr) : nullptr;
    PJ* norm = raw != nullptr ? proj_normalize_for_visualization(ctx, raw) : nullptr;
    proj_destroy(raw);
    proj_destroy(dst);
    return norm;
  }
};

CrsTransform::CrsTransform(const std::string& crs) : crs_(crs), impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.ctx = proj_context_create();
  proj_log_level(m.ctx, PJ_LOG_NONE);  // errors come back as exceptions, not stderr chatter
  auto fail = [&](const std::string& why) { return InputError("unknown CRS '" + crs + "': " + why); };
  PJ* src = proj_create(m.ctx, crs.c_str());
  if (src == nullptr) throw fail(proj_reason(m.ctx));
  if (proj_is_crs(src) == 0) {
    proj_destroy(src);
    throw fail("not a coordinate reference system");
  }
  PJ* target = proj_create(m.ctx, "EPSG:4979");
  const bool split = proj_get_type(src) == PJ_TYPE_COMPOUND_CRS && best_operation_is_ballpark(m.ctx, src, target);
  proj_destroy(target);
  if (split) {
    PJ* horizontal = proj_crs_get_sub_crs(m.ctx, src, 0);
    m.op = horizontal != nullptr ? m.normalized_op(horizontal, "EPSG:4979") : nullptr;
    proj_destroy(horizontal);
    PJ* egm = proj_create(m.ctx, "EPSG:4326+5773");  // WGS84 + EGM96 height
    PJ* wgs84_3d = proj_create(m.ctx, "EPSG:4979");
    if (egm != nullptr && wgs84_3d != nullptr && !best_operation_is_ballpark(m.ctx, egm, wgs84_3d))
      m.geoid = m.normalized_op(egm, "EPSG:4979");
    proj_destroy(wgs84_3d);
    proj_destroy(egm);
    m.method = m.geoid != nullptr ? "horizontal sub-CRS + height as EGM96 (no grid for the vertical datum)"
                                  : "horizontal sub-CRS + height passed through (ballpark: no geoid grid)";
  } else {
    m.op = m.normalized_op(src, "EPSG:4979");
    m.method = "PROJ operation to EPSG:4979";
  }
  proj_destroy(src);
  if (m.op == nullptr) throw fail("no transformation to WGS84: " + proj_reason(m.ctx));
}

CrsTransform::~CrsTransform() = default;

const std::string& CrsTransform::method() const { return impl_->method; }

Eigen::Vector3d CrsTransform::to_lla(const Eigen::Vector3d& xyz) const {
  if (!xyz.allFinite()) throw InputError("CRS '" + crs_ + "': coordinate is not finite");
  PJ_COORD c = proj_coord(xyz.x(), xyz.y(), xyz.z(), 0.0);
  proj_errno_reset(impl_->op);
  PJ_COORD out = proj_trans(impl_->op, PJ_FWD, c);
  if (impl_->geoid != nullptr && std::isfinite(out.v[0])) out = proj_trans(impl_->geoid, PJ_FWD, out);
  const Eigen::Vector3d lla(out.v[1], out.v[0], out.v[2]);
  if (!lla.allFinite() || std::abs(lla.x()) > 90.0)
    throw InputError("CRS '" + crs_ + "': cannot transform (" + std::to_string(xyz.x()) + ", " +
                     std::to_string(xyz.y()) + ", " + std::to_string(xyz.z()) + ") to WGS84");
  return lla;
}

}  // namespace twinslam::twin
