#include "energy.hpp"

namespace medax::vmas {

void SphereTerms::set(const std::vector<Sphere>& spheres) {
  for (auto& column : m) column.resize(spheres.size());
  for (std::size_t j = 0; j < spheres.size(); ++j) {
    const auto mono = monomials(spheres[j]);
    for (int i = 0; i < 14; ++i) m[i][j] = mono[i];
  }
}

ClusterStats cluster_stats(const VmasInput& in, const std::vector<PackedQuadric>& quadrics, const Index* members,
                           std::size_t count, const Sphere& s, double lambda) {
  ClusterStats st;
  const auto m = monomials(s);
  for (std::size_t i = 0; i < count; ++i) {
    const Index v = members[i];
    const double e = vertex_energy(quadrics[v], in.points[v], lambda * in.areas[v], m.data());
    st.energy += e;
    st.area += in.areas[v];
    if (e > st.split_energy) {
      st.split_energy = e;
      st.split_vertex = v;
    }
  }
  st.error = st.area > 0 ? st.energy / st.area : 0.0;
  return st;
}

std::vector<PackedQuadric> vertex_normal_quadrics(const VmasInput& in) {
  std::vector<PackedQuadric> out(in.size());
  for (Index v = 0; v < in.size(); ++v)
    out[v] = PackedQuadric::from(Quadric::plane(in.points[v], in.normals[v], in.areas[v]));
  return out;
}

}  // namespace medax::vmas
