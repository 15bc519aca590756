#pragma once
// A 3-D KD-tree over float points (nanoflann's single index), with the two queries registration needs and nothing
// allocated per query. Why not PCL's KdTreeFLANN: per query the wrapper copies the point into a heap vector,
// allocates its result vectors and opens an OpenMP region, which costs more than a 1-NN search in a tile (ICP time
// per point and association 1.91 us through it, 0.68 us on FLANN's index directly). Why not FLANN's index directly:
// nanoflann's (the same kind of tree, statically dispatched result sets) took 0.55 us, and the statistical outlier
// removal on ~930 points 0.92 instead of 1.14 ms, with the same answers (bench_registration, 1 km^2). Private to the
// library (src/): the tree library stays out of every public header.
#include <cstddef>
#include <limits>
#include <memory>
#include <vector>

namespace twinslam::registration {

class KdTree3f {
 public:
  static constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
  static constexpr std::size_t kMaxK = 33;  // knn(): k at most (32 neighbours + the query point itself)

  explicit KdTree3f(std::vector<float> xyz);  // 3 floats per point; an empty vector gives an empty tree
  ~KdTree3f();
  KdTree3f(KdTree3f&&) noexcept;
  KdTree3f& operator=(KdTree3f&&) noexcept;

  std::size_t size() const { return xyz_.size() / 3; }
  bool empty() const { return xyz_.empty(); }
  const float* point(std::size_t i) const { return xyz_.data() + 3 * i; }

  // The point closest to q with squared distance < radius_sq (kNone if there is none); dist_sq gets its distance.
  std::size_t nearest_within(const float* q, float radius_sq, float& dist_sq) const;
  // Squared distances of the k (<= kMaxK) nearest points, ascending, into dist_sq[0..k); returns how many were found.
  std::size_t knn(const float* q, std::size_t k, float* dist_sq) const;

 private:
  struct Tree;
  std::vector<float> xyz_;
  std::unique_ptr<Tree> tree_;
};

}  // namespace twinslam::registration
