#include <medax/services/kdtree.hpp>

#include <nanoflann.hpp>

#include <cmath>

namespace medax::services {

namespace {
/// nanoflann's dataset adaptor over a vector of Vec3.
struct Cloud {
  const std::vector<Vec3>* points;
  std::size_t kdtree_get_point_count() const { return points->size(); }
  double kdtree_get_pt(std::size_t i, std::size_t dim) const { return (*points)[i][static_cast<int>(dim)]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const { return false; }
};
using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Cloud>, Cloud, 3, Index>;
}  // namespace

struct PointIndex::Impl {
  Cloud cloud;
  Tree tree;
  explicit Impl(const std::vector<Vec3>& points)
      : cloud{&points}, tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10)) {
    tree.buildIndex();
  }
};

PointIndex::PointIndex(const std::vector<Vec3>& points) : impl_(std::make_unique<Impl>(points)) {}
PointIndex::~PointIndex() = default;
PointIndex::PointIndex(PointIndex&&) noexcept = default;
PointIndex& PointIndex::operator=(PointIndex&&) noexcept = default;

const std::vector<Vec3>& PointIndex::points() const { return *impl_->cloud.points; }

std::pair<Index, double> PointIndex::nearest(const Vec3& q) const {
  Index index = 0;
  double d2 = 0;
  impl_->tree.knnSearch(q.data(), 1, &index, &d2);
  return {index, std::sqrt(d2)};
}

std::vector<std::pair<Index, double>> PointIndex::k_nearest(const Vec3& q, std::size_t k) const {
  std::vector<Index> indices(k);
  std::vector<double> d2(k);
  const std::size_t found = impl_->tree.knnSearch(q.data(), k, indices.data(), d2.data());
  std::vector<std::pair<Index, double>> out(found);
  for (std::size_t i = 0; i < found; ++i) out[i] = {indices[i], std::sqrt(d2[i])};
  return out;
}

std::vector<std::pair<Index, double>> PointIndex::within(const Vec3& q, double radius) const {
  std::vector<std::pair<Index, double>> matches;
  impl_->tree.radiusSearch(q.data(), radius * radius, matches, nanoflann::SearchParams(32, 0, true));
  for (auto& m : matches) m.second = std::sqrt(m.second);
  return matches;
}

}  // namespace medax::services
