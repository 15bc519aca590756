// KdTree3f over nanoflann's KDTreeSingleIndexAdaptor (see kdtree.hpp for the choice).
#include "kdtree.hpp"

#include <algorithm>

#include <nanoflann.hpp>

namespace twinslam::registration {
namespace {

// nanoflann reads the points through this adaptor: the tree's own float array, 3 per point.
// The buffer, not the vector: a moved KdTree3f keeps the buffer but not the vector object.
struct Points {
  const float* xyz;
  std::size_t n;
  std::size_t kdtree_get_point_count() const { return n; }
  float kdtree_get_pt(std::size_t i, std::size_t d) const { return xyz[3 * i + d]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const { return false; }
};

using Index = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, Points>, Points, 3, std::size_t>;

// The closest point strictly within the radius: the tree prunes by worstDist() from the first node on.
struct NearestWithin {
  using DistanceType = float;
  using IndexType = std::size_t;
  float worst;
  std::size_t index = KdTree3f::kNone;
  bool full() const { return true; }
  bool addPoint(float dist, std::size_t i) {
    if (dist < worst) worst = dist, index = i;
    return true;
  }
  float worstDist() const { return worst; }
};

// The k closest, kept sorted by insertion in a fixed array (k is small): nothing allocated per query.
struct Nearest {
  using DistanceType = float;
  using IndexType = std::size_t;
  std::size_t k, n = 0;
  float d[KdTree3f::kMaxK];
  bool full() const { return n == k; }
  bool addPoint(float dist, std::size_t) {
    if (n == k && dist >= d[k - 1]) return true;
    std::size_t i = n < k ? n++ : k - 1;
    for (; i > 0 && d[i - 1] > dist; --i) d[i] = d[i - 1];
    d[i] = dist;
    return true;
  }
  float worstDist() const { return n == k ? d[k - 1] : std::numeric_limits<float>::max(); }
};

}  // namespace

// Leaves of at most 16 points. Copying the points into leaf order after the build (as FLANN's reorder option did)
// made no difference in bench_registration here, so the tree reads them through its index array.
struct KdTree3f::Tree {
  explicit Tree(const std::vector<float>& xyz) : points{xyz.data(), xyz.size() / 3}, index(3, points, {16}) {}
  Points points;
  Index index;
};

KdTree3f::KdTree3f(std::vector<float> xyz) : xyz_(std::move(xyz)) {
  xyz_.resize(xyz_.size() / 3 * 3);
  if (!xyz_.empty()) tree_ = std::make_unique<Tree>(xyz_);
}
KdTree3f::~KdTree3f() = default;
KdTree3f::KdTree3f(KdTree3f&&) noexcept = default;
KdTree3f& KdTree3f::operator=(KdTree3f&&) noexcept = default;

std::size_t KdTree3f::nearest_within(const float* q, float radius_sq, float& dist_sq) const {
  if (!tree_) return kNone;
  NearestWithin result{radius_sq};
  tree_->index.findNeighbors(result, q, nanoflann::SearchParams());
  dist_sq = result.worst;
  return result.index;
}

std::size_t KdTree3f::knn(const float* q, std::size_t k, float* dist_sq) const {
  k = std::min({k, kMaxK, size()});
  if (!tree_ || k == 0) return 0;
  Nearest result{k, 0, {}};
  tree_->index.findNeighbors(result, q, nanoflann::SearchParams());
  std::copy(result.d, result.d + result.n, dist_sq);
  return result.n;
}

}  // namespace twinslam::registration
