#include "output.hpp"

#include <medax/ply.hpp>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <numeric>
#include <ostream>

namespace medax::msd {

MedialComplex skeleton_complex(const Diagram& diagram) {
  const Skeleton& skeleton = diagram.skeleton;
  MedialComplex medial;
  medial.add(kIsSite);
  medial.add(kInitialRadius);
  for (std::size_t v = 0; v < skeleton.vertices.size(); ++v) {
    const Primitive& sphere = diagram.primitives[v];  // elements list the vertices first
    double radius = sphere.initial_radius;
    if (sphere.fitted && !sphere.radius.empty())
      radius = std::accumulate(sphere.radius.begin(), sphere.radius.end(), 0.0) / sphere.radius.size();
    const Index id = medial.add_vertex(skeleton.vertices[v], radius);
    medial.get(kIsSite)[id] = skeleton.is_site[v] ? 1 : 0;
    medial.get(kInitialRadius)[id] = sphere.initial_radius;
  }
  for (const Segment& e : skeleton.edges) medial.add_edge(e[0], e[1]);
  for (const Tri& t : skeleton.triangles) medial.add_face(t[0], t[1], t[2]);
  return medial;
}

Counts count_elements(const Diagram& diagram) {
  Counts counts;
  counts.vertices = diagram.skeleton.vertices.size();
  counts.edges = diagram.skeleton.edges.size();
  counts.triangles = diagram.skeleton.triangles.size();
  counts.discrete = counts.vertices + counts.edges + counts.triangles;
  counts.continuous = 3 * counts.vertices;
  for (const Primitive& p : diagram.primitives) {
    if (p.fitted) counts.continuous += p.shape.size();
    else ++counts.failed_primitives;
  }
  return counts;
}

void write_primitives_ply(std::ostream& out, const std::vector<Primitive>& primitives, const Similarity& to_input) {
  std::vector<Vec3> points, base, direction;
  std::vector<double> radius;
  std::vector<Tri> faces;
  std::vector<long long> face_primitive;
  for (std::size_t id = 0; id < primitives.size(); ++id) {
    const Primitive& p = primitives[id];
    if (!p.fitted) continue;
    const auto offset = static_cast<Index>(points.size());
    const std::vector<Vec3> vertices = primitive_vertices(p.shape, p.radius);
    for (std::size_t i = 0; i < vertices.size(); ++i) {
      points.push_back(to_input.apply(vertices[i]));
      base.push_back(to_input.apply(p.shape.base[i]));
      direction.push_back(p.shape.direction[i]);
      radius.push_back(to_input.apply_length(p.radius[i]));
    }
    for (const Tri& f : p.shape.faces) {
      faces.push_back({f[0] + offset, f[1] + offset, f[2] + offset});
      face_primitive.push_back(static_cast<long long>(id));
    }
  }
  PlyElement vertex("vertex", points.size());
  vertex.positions(points);
  const char* axes[3] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k) vertex.real(fmt::format("b{}", axes[k]), [&, k](std::size_t i) { return base[i][k]; });
  for (int k = 0; k < 3; ++k)
    vertex.real(fmt::format("d{}", axes[k]), [&, k](std::size_t i) { return direction[i][k]; });
  vertex.real("radius", [&](std::size_t i) { return radius[i]; });
  PlyElement face("face", faces.size());
  face.triangles(faces);
  face.integer("primitive", [&](std::size_t i) { return face_primitive[i]; });
  write_ply(out, "medax msd primitives: vertex = base + radius * direction", {vertex, face});
}

namespace {

nlohmann::json phase_times(const std::vector<IterationLog>& log) {
  double projection = 0, construction = 0, fitting = 0, energy = 0;
  for (const IterationLog& it : log) {
    projection += it.seconds_projection;
    construction += it.seconds_construction;
    fitting += it.seconds_fitting;
    energy += it.seconds_energy;
  }
  const double n = log.empty() ? 1.0 : static_cast<double>(log.size());
  return {{"total", {{"projection", projection}, {"construction", construction}, {"fitting", fitting},
                     {"energy", energy}}},
          {"per_iteration", {{"projection", projection / n}, {"construction", construction / n},
                             {"fitting", fitting / n}, {"energy", energy / n},
                             {"all", (projection + construction + fitting + energy) / n}}}};
}

nlohmann::json additions(const std::vector<RoundLog>& rounds) {
  nlohmann::json list = nlohmann::json::array();
  for (const RoundLog& r : rounds)
    list.push_back({{"uncovered_regions", r.uncovered_regions}, {"added", r.sites_added},
                    {"largest_volume", r.largest_region_volume}, {"seconds", r.seconds}});
  return list;
}

}  // namespace

void write_summary_json(std::ostream& out, const Summary& s) {
  const Counts& c = s.counts;
  const double input_size = 3.0 * s.input_vertices + s.input_triangles;
  const OptimisationResult& r = *s.result;
  nlohmann::json j = {
      {"N_d", c.discrete},
      {"N_c", c.continuous},
      {"vertices", c.vertices},
      {"unique_edges", c.edges},
      {"triangles", c.triangles},
      {"failed_primitives", c.failed_primitives},
      {"coverage", {{"area", s.covered_area}, {"vertices", s.covered_vertices}}},
      {"compression_ratio", input_size / static_cast<double>(c.continuous + c.discrete)},
      {"energy", {{"total", r.best.energy.total}, {"coverage", r.best.energy.coverage},
                  {"centroid", r.best.energy.centroid}, {"count", r.best.energy.count}}},
      {"iterations", r.log.size()},
      {"rounds", r.rounds},
      {"stop_reason", r.stop_reason},
      {"tets", r.tets},
      {"delta", r.delta},
      {"sites_added", additions(r.additions)},
      {"radius_rule", s.radius_rule},
      {"reconstruction", s.reconstruction},
      {"seconds", {{"total", s.seconds_total}, {"tetrahedralisation", r.seconds_tetrahedralisation},
                   {"final_fit", r.seconds_final_fit}, {"reconstruction", s.seconds_reconstruction},
                   {"phases", phase_times(r.log)}}},
  };
  out << j.dump(2) << '\n';
}

}  // namespace medax::msd
