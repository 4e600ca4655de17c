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

Counts count_elements(const Diagram& diagram, const std::vector<RefinedPrimitive>& final_primitives) {
  Counts counts = count_elements(diagram);
  counts.continuous = 3 * counts.vertices;
  for (const RefinedPrimitive& p : final_primitives) counts.continuous += p.mesh.vertices.size();
  return counts;
}

std::vector<RefinedPrimitive> unrefined_primitives(const std::vector<Primitive>& primitives) {
  std::vector<RefinedPrimitive> result(primitives.size());
  for (std::size_t k = 0; k < primitives.size(); ++k) {
    const Primitive& p = primitives[k];
    RefinedPrimitive& r = result[k];
    r.note = p.fitted ? "refinement off" : p.failure;
    if (!p.fitted) continue;
    r.mesh = primitive_mesh(p);
    r.base = p.shape.base;
    r.input_vertex.assign(r.mesh.vertices.size(), kNotInput);
  }
  return result;
}

namespace {

/// The PLY's vertex columns: every final primitive's vertices, in the input frame.
struct PlyVertices {
  std::vector<Vec3> points, base, direction;
  std::vector<double> radius;
  std::vector<long long> input_vertex;
};

void append_vertices(const RefinedPrimitive& p, const Similarity& to_input, PlyVertices& v) {
  for (std::size_t i = 0; i < p.mesh.vertices.size(); ++i) {
    const Vec3 offset = p.mesh.vertices[i] - p.base[i];
    const double length = offset.norm();
    v.points.push_back(to_input.apply(p.mesh.vertices[i]));
    v.base.push_back(to_input.apply(p.base[i]));
    v.direction.push_back(length > 0 ? Vec3(offset / length) : Vec3::Zero());
    v.radius.push_back(to_input.apply_length(length));
    const bool is_input = i < p.input_vertex.size() && p.input_vertex[i] != kNotInput;
    v.input_vertex.push_back(is_input ? static_cast<long long>(p.input_vertex[i]) : -1);
  }
}

}  // namespace

void write_primitives_ply(std::ostream& out, const std::vector<RefinedPrimitive>& final_primitives,
                          const Similarity& to_input) {
  PlyVertices v;
  std::vector<Tri> faces;
  std::vector<long long> face_primitive, face_refined;
  for (std::size_t id = 0; id < final_primitives.size(); ++id) {
    const RefinedPrimitive& p = final_primitives[id];
    const auto offset = static_cast<Index>(v.points.size());
    append_vertices(p, to_input, v);
    for (const Tri& f : p.mesh.faces) {
      faces.push_back({f[0] + offset, f[1] + offset, f[2] + offset});
      face_primitive.push_back(static_cast<long long>(id));
      face_refined.push_back(p.refined ? 1 : 0);
    }
  }
  PlyElement vertex("vertex", v.points.size());
  vertex.positions(v.points);
  const char* axes[3] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k) vertex.real(fmt::format("b{}", axes[k]), [&, k](std::size_t i) { return v.base[i][k]; });
  for (int k = 0; k < 3; ++k)
    vertex.real(fmt::format("d{}", axes[k]), [&, k](std::size_t i) { return v.direction[i][k]; });
  vertex.real("radius", [&](std::size_t i) { return v.radius[i]; });
  vertex.integer("input_vertex", [&](std::size_t i) { return v.input_vertex[i]; });
  PlyElement face("face", faces.size());
  face.triangles(faces);
  face.integer("primitive", [&](std::size_t i) { return face_primitive[i]; });
  face.integer("refined", [&](std::size_t i) { return face_refined[i]; });
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

nlohmann::json refinement(const RefinementSummary& r) {
  nlohmann::json notes = nlohmann::json::array();
  for (const auto& [id, note] : r.notes) notes.push_back({{"primitive", id}, {"note", note}});
  return {{"enabled", r.enabled}, {"refined", r.refined}, {"unrefined", r.unrefined}, {"unrefined_notes", notes},
          {"seconds", r.seconds}, {"cpu_seconds", r.cpu_seconds}};
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
      {"refinement", refinement(s.refinement)},
      {"seconds", {{"total", s.seconds_total}, {"tetrahedralisation", r.seconds_tetrahedralisation},
                   {"final_fit", r.seconds_final_fit}, {"refinement", s.refinement.seconds},
                   {"reconstruction", s.seconds_reconstruction},
                   {"phases", phase_times(r.log)}}},
  };
  out << j.dump(2) << '\n';
}

}  // namespace medax::msd
