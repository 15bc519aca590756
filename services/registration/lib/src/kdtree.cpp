// KdTree3f over FLANN's KDTreeSingleIndex (see kdtree.hpp for why not through PCL's KdTreeFLANN).
#include "kdtree.hpp"

#include <algorithm>

#include <flann/algorithms/dist.h>
#include <flann/algorithms/kdtree_single_index.h>

namespace twinslam::registration {
namespace {

using Index = flann::KDTreeSingleIndex<flann::L2_Simple<float>>;

// The closest point strictly within the radius: the tree prunes by worstDist() from the first node on.
class NearestWithin final : public flann::ResultSet<float> {
 public:
  explicit NearestWithin(float radius_sq) : worst_(radius_sq) {}
  bool full() const override { return true; }
  void addPoint(float dist, size_t index) override {
    if (dist < worst_) worst_ = dist, index_ = index;
  }
  float worstDist() const override { return worst_; }
  float worst_;
  std::size_t index_ = KdTree3f::kNone;
};

// The k closest, kept sorted by insertion in a fixed array (k is small): nothing allocated per query.
class Nearest final : public flann::ResultSet<float> {
 public:
  explicit Nearest(std::size_t k) : k_(k) {}
  bool full() const override { return n_ == k_; }
  void addPoint(float dist, size_t) override {
    if (n_ == k_ && dist >= d_[k_ - 1]) return;
    std::size_t i = n_ < k_ ? n_++ : k_ - 1;
    for (; i > 0 && d_[i - 1] > dist; --i) d_[i] = d_[i - 1];
    d_[i] = dist;
  }
  float worstDist() const override { return n_ == k_ ? d_[k_ - 1] : std::numeric_limits<float>::max(); }
  std::size_t k_, n_ = 0;
  float d_[KdTree3f::kMaxK];
};

}  // namespace

// Leaves of at most 16 points (10, FLANN's default, and 4 were no faster in bench_registration, 32 no better);
// reorder: the tree keeps its points in leaf order (cache-friendly leaf scans, one more copy of 12 B per point).
struct KdTree3f::Tree {
  explicit Tree(std::vector<float>& xyz)
      : index(flann::Matrix<float>(xyz.data(), xyz.size() / 3, 3), flann::KDTreeSingleIndexParams(16, true)) {
    index.buildIndex();
  }
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
  NearestWithin result(radius_sq);
  tree_->index.findNeighbors(result, q, flann::SearchParams(-1, 0.0f, false));
  dist_sq = result.worst_;
  return result.index_;
}

std::size_t KdTree3f::knn(const float* q, std::size_t k, float* dist_sq) const {
  k = std::min({k, kMaxK, size()});
  if (!tree_ || k == 0) return 0;
  Nearest result(k);
  tree_->index.findNeighbors(result, q, flann::SearchParams(-1, 0.0f, false));
  std::copy(result.d_, result.d_ + result.n_, dist_sq);
  return result.n_;
}

}  // namespace twinslam::registration
