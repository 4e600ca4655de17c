// Output of a Durix run (notes §1.4): the medial complex dual to M_w with sheet labels and path
// types, M_w itself, the correspondence both ways, and the surface segmentation by voting.
#include "output.hpp"

#include <medax/services/kdtree.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <ostream>

namespace medax::durix {

std::array<int, 3> label_colour(int label) {
  if (label < 0) return {160, 160, 160};
  // Golden-ratio hue walk, full saturation-ish: neighbouring labels get distant hues.
  const double h = std::fmod(0.13 + 0.618033988749895 * label, 1.0) * 6.0;
  const double s = 0.65, v = 0.95 - 0.25 * ((label / 7) % 2);
  const int i = static_cast<int>(h);
  const double f = h - i, p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
  double r = v, g = t, b = p;
  switch (i % 6) {
    case 0: r = v, g = t, b = p; break;
    case 1: r = q, g = v, b = p; break;
    case 2: r = p, g = v, b = t; break;
    case 3: r = p, g = q, b = v; break;
    case 4: r = t, g = p, b = v; break;
    default: r = v, g = p, b = q; break;
  }
  return {int(r * 255 + 0.5), int(g * 255 + 0.5), int(b * 255 + 0.5)};
}

void build_output(const Engine& engine, const SurfaceMesh& mesh, DurixResult& result) {
  const Dual& d = engine.d;
  DurixReport& report = result.report;
  MedialComplex& mc = result.medial;

  // Nodes: solid cells in cell order.
  std::vector<Index> node(d.num_cells(), kNoId);
  for (CellId c = 0; c < d.num_cells(); ++c)
    if (d.solid(c)) {
      node[c] = mc.add_vertex(d.centre(c), d.radius(c));
      const auto& q = d.cell(c);
      mc.generators.push_back({q[0], q[1], q[2], q[3]});
      report.outside_centres_left += !engine.centre_inside.empty() && !engine.centre_inside[c];
    }
  mc.generator_kind = "mesh_vertex";
  const std::size_t nv = mc.num_vertices();

  // Sheet labels renumbered compactly by first face (in DT edge order).
  std::map<int, int> renumber;
  for (EdgeId e = 0; e < d.num_edges(); ++e)
    if (d.volumetric(e) && d.label(e) >= 0 && !renumber.count(d.label(e)))
      renumber.emplace(d.label(e), static_cast<int>(renumber.size()));
  const auto sheet_of = [&](EdgeId e) { return d.volumetric(e) && d.label(e) >= 0 ? renumber.at(d.label(e)) : -1; };
  const int face_sheets = static_cast<int>(renumber.size());

  // Medial edges: facets between solid cells, in cell order. Curve sheets: components of
  // degree-0 edges joined at nodes.
  std::vector<Facet> medial_edges;
  for (CellId c = 0; c < d.num_cells(); ++c) {
    if (!d.solid(c)) continue;
    for (int k = 0; k < 4; ++k) {
      const CellId n = d.neighbour(c, k);
      if (d.solid(n) && c < n) medial_edges.push_back({c, std::uint8_t(k)});
    }
  }
  std::vector<int> curve(nv, -1);  // union-find over nodes along degree-0 edges
  const auto find = [&](int x) {
    while (curve[x] != x) x = curve[x] = curve[curve[x]];
    return x;
  };
  std::vector<int> degree(medial_edges.size());
  for (std::size_t i = 0; i < medial_edges.size(); ++i) {
    degree[i] = d.degree(medial_edges[i]);
    if (degree[i] != 0) continue;
    const int a = static_cast<int>(node[medial_edges[i].cell]), b = static_cast<int>(node[d.other_cell(medial_edges[i])]);
    if (curve[a] < 0) curve[a] = a;
    if (curve[b] < 0) curve[b] = b;
    curve[find(a)] = find(b);
  }
  std::map<int, int> curve_label;
  for (std::size_t i = 0; i < medial_edges.size(); ++i)
    if (degree[i] == 0) {
      const int root = find(static_cast<int>(node[medial_edges[i].cell]));
      if (!curve_label.count(root)) curve_label.emplace(root, face_sheets + static_cast<int>(curve_label.size()));
    }
  report.sheets = static_cast<std::size_t>(face_sheets);
  report.curve_sheets = curve_label.size();

  std::vector<int> edge_type, edge_degree, edge_sheet;
  for (std::size_t i = 0; i < medial_edges.size(); ++i) {
    const Facet& t = medial_edges[i];
    mc.add_edge(node[t.cell], node[d.other_cell(t)]);
    const auto v = d.facet_vertices(t);
    int labels[3], nl = 0;
    for (int j = 0; j < 3; ++j) {
      const EdgeId e = d.edge_of(t.cell, v[j], v[(j + 1) % 3]);
      if (d.volumetric(e)) labels[nl++] = sheet_of(e);
    }
    int type = kRegular, sheet = -1;
    switch (degree[i]) {
      case 0:
        type = kCurve;
        sheet = curve_label.at(find(static_cast<int>(node[t.cell])));
        break;
      case 1:
        type = kBoundary;
        sheet = labels[0];
        break;
      case 2:
        if (labels[0] != labels[1]) type = d.forced(t) ? kForcedSingular : kSingular;
        else if (d.forced(t)) type = kForcedSingular;
        else sheet = labels[0];
        break;
      default:
        type = (labels[0] == labels[1] && labels[1] == labels[2]) ? kProblematic : kSingular;
        break;
    }
    edge_type.push_back(type);
    edge_degree.push_back(degree[i]);
    edge_sheet.push_back(sheet);
  }
  report.medial_edges = medial_edges.size();

  // Medial faces: Voronoi polygons of the volumetric edges, fan-triangulated from their first
  // node; the fan diagonals are extra edges of type kFanDiagonal.
  std::vector<int> face_sheet, face_polygon, face_gen_a, face_gen_b;
  std::vector<CellId> ring;
  int polygon = 0;
  for (EdgeId e = 0; e < d.num_edges(); ++e) {
    if (!d.volumetric(e)) continue;
    d.ring(e, ring);
    const int sheet = sheet_of(e);
    for (std::size_t i = 1; i + 1 < ring.size(); ++i) {
      mc.add_face(node[ring[0]], node[ring[i]], node[ring[i + 1]]);
      face_sheet.push_back(sheet);
      face_polygon.push_back(polygon);
      face_gen_a.push_back(static_cast<int>(d.edge_vertices(e)[0]));
      face_gen_b.push_back(static_cast<int>(d.edge_vertices(e)[1]));
      if (i >= 2) {
        mc.add_edge(node[ring[0]], node[ring[i]]);
        edge_type.push_back(kFanDiagonal);
        edge_degree.push_back(-1);
        edge_sheet.push_back(sheet);
      }
    }
    ++polygon;
  }
  report.medial_faces = static_cast<std::size_t>(polygon);
  report.nodes = nv;

  // Node labels: type (1 boundary, 2 regular, 3 singular) and sheet (-1: several or none).
  std::vector<int> node_type(nv), node_sheet(nv, -2), node_flat(nv, 0);
  for (CellId c = 0; c < d.num_cells(); ++c)
    if (d.solid(c)) {
      node_type[node[c]] = std::min(3, d.node_components(c));
      node_flat[node[c]] = d.flat(c);
    }
  const auto vote_node = [&](Index n, int sheet) {
    int& s = node_sheet[n];
    s = (s == -2 || s == sheet) ? sheet : -1;
  };
  for (std::size_t i = 0; i < mc.faces.size(); ++i)
    for (Index n : mc.faces[i]) vote_node(n, face_sheet[i]);
  for (std::size_t i = 0; i < medial_edges.size(); ++i)
    if (degree[i] == 0) {
      vote_node(mc.edges[i][0], edge_sheet[i]);
      vote_node(mc.edges[i][1], edge_sheet[i]);
    }
  for (int& s : node_sheet)
    if (s == -2) s = -1;

  mc.vertex_props.labels.add("node_type", nv) = node_type;
  mc.vertex_props.labels.add("sheet", nv) = node_sheet;
  mc.vertex_props.labels.add("flat", nv) = node_flat;
  mc.edge_props.labels.add("path_type", mc.edges.size()) = edge_type;
  mc.edge_props.labels.add("degree", mc.edges.size()) = edge_degree;
  mc.edge_props.labels.add("sheet", mc.edges.size()) = edge_sheet;
  mc.face_props.labels.add("sheet", mc.faces.size()) = face_sheet;
  mc.face_props.labels.add("voronoi_face", mc.faces.size()) = face_polygon;
  mc.face_props.labels.add("generator_a", mc.faces.size()) = face_gen_a;
  mc.face_props.labels.add("generator_b", mc.faces.size()) = face_gen_b;
  report.problematic_left = 0;
  for (std::size_t i = 0; i < medial_edges.size(); ++i)
    if (edge_type[i] == kProblematic) ++report.problematic_left;

  // M_w, compact, with its face -> node map.
  const std::size_t np = d.num_points();
  result.vertex_removed.assign(np, 0);
  std::vector<Index> compact(np, kNoId);
  for (Index v = 0; v < np; ++v) {
    if (d.on_surface(v)) {
      compact[v] = static_cast<Index>(result.surface.vertices.size());
      result.surface.vertices.push_back(d.point(v));
      result.surface_vertex.push_back(v);
    } else {
      result.vertex_removed[v] = 1;
    }
  }
  const std::vector<Facet> surface = d.surface_facets();
  std::vector<CellId> surface_cell;
  for (const Facet& f : surface) {
    const Tri t = d.oriented_surface_triangle(f);
    result.surface.faces.push_back({compact[t[0]], compact[t[1]], compact[t[2]]});
    const CellId c = d.solid(f.cell) ? f.cell : d.other_cell(f);
    surface_cell.push_back(c);
    result.surface_face_node.push_back(node[c]);
  }
  report.surface_vertices = result.surface.vertices.size();
  report.surface_faces = result.surface.faces.size();

  // Segmentation by voting (notes §1.4): a node whose faces (or curve edges) carry one label
  // votes it onto its 4 vertices and onto the removed vertices it witnesses.
  std::vector<std::map<int, int>> votes(np);
  for (CellId c = 0; c < d.num_cells(); ++c) {
    if (!d.solid(c)) continue;
    const int s = node_sheet[node[c]];
    if (s < 0) continue;
    for (Index v : d.cell(c)) ++votes[v][s];
    if (const auto it = engine.attached.find(c); it != engine.attached.end())
      for (Index v : it->second) ++votes[v][s];
  }
  result.vertex_sheet.assign(np, -1);
  for (Index v = 0; v < np; ++v) {
    int best = -1, count = 0;
    for (const auto& [s, n] : votes[v])
      if (n > count) best = s, count = n;
    result.vertex_sheet[v] = best;
  }
  // Vertices with no vote take the most frequent label of their mesh neighbours (a few rounds).
  std::vector<std::vector<Index>> adjacency(np);
  for (const Tri& t : mesh.faces)
    for (int i = 0; i < 3; ++i) {
      adjacency[t[i]].push_back(t[(i + 1) % 3]);
      adjacency[t[i]].push_back(t[(i + 2) % 3]);
    }
  for (int round = 0; round < 64; ++round) {
    bool changed = false;
    std::vector<int> next = result.vertex_sheet;
    for (Index v = 0; v < np; ++v) {
      if (result.vertex_sheet[v] >= 0) continue;
      std::map<int, int> around;
      for (Index w : adjacency[v])
        if (result.vertex_sheet[w] >= 0) ++around[result.vertex_sheet[w]];
      int best = -1, count = 0;
      for (const auto& [s, n] : around)
        if (n > count) best = s, count = n;
      if (best >= 0) next[v] = best, changed = true;
    }
    result.vertex_sheet.swap(next);
    if (!changed) break;
  }
  const auto majority = [&](const Tri& t) {
    const int a = result.vertex_sheet[t[0]], b = result.vertex_sheet[t[1]], c = result.vertex_sheet[t[2]];
    if (a == b || a == c) return a;
    if (b == c) return b;
    return std::max({a, b, c}) < 0 ? -1 : (a >= 0 ? a : b >= 0 ? b : c);
  };
  result.face_sheet.reserve(mesh.faces.size());
  for (const Tri& t : mesh.faces) result.face_sheet.push_back(majority(t));
  for (std::size_t i = 0; i < surface.size(); ++i) {
    const int s = node_sheet[node[surface_cell[i]]];
    const Tri& t = result.surface.faces[i];
    result.surface_face_sheet.push_back(
        s >= 0 ? s
               : majority({result.surface_vertex[t[0]], result.surface_vertex[t[1]], result.surface_vertex[t[2]]}));
  }

  // Input vertex -> node: a cell of it on M_w, the witness when removed.
  result.vertex_node.assign(np, kNoId);
  for (CellId c = 0; c < d.num_cells(); ++c)
    if (d.solid(c))
      for (Index v : d.cell(c))
        if (result.vertex_node[v] == kNoId) result.vertex_node[v] = node[c];
  for (Index v = 0; v < np; ++v)
    if (result.vertex_removed[v] && engine.witness[v] != kNoId && d.solid(engine.witness[v]))
      result.vertex_node[v] = node[engine.witness[v]];

  // ε guarantee, end to end (notes §5.6): removed vertices against the output balls.
  report.max_removed_excess = 0;
  if (nv > 0) {
    services::PointIndex index(mc.centres);
    for (Index v = 0; v < np; ++v) {
      if (!result.vertex_removed[v]) continue;
      const Vec3& p = d.point(v);
      double best = std::numeric_limits<double>::infinity();
      if (result.vertex_node[v] != kNoId)
        best = (p - mc.centres[result.vertex_node[v]]).norm() - mc.radii[result.vertex_node[v]];
      for (const auto& [i, dist] : index.k_nearest(p, 16)) best = std::min(best, dist - mc.radii[i]);
      report.max_removed_excess = std::max(report.max_removed_excess, best);
    }
  }
}

void write_segmentation_ply(std::ostream& out, const SurfaceMesh& mesh, const DurixResult& r) {
  out << "ply\nformat ascii 1.0\ncomment medax durix: surface segmentation (sheet per vertex and face)\n";
  out << "element vertex " << mesh.vertices.size()
      << "\nproperty double x\nproperty double y\nproperty double z\nproperty uchar red\nproperty uchar green\n"
         "property uchar blue\nproperty int sheet\nproperty int removed\nproperty int node\n";
  out << "element face " << mesh.faces.size()
      << "\nproperty list uchar int vertex_indices\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
         "property int sheet\nend_header\n";
  out.precision(17);
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    const auto c = label_colour(r.vertex_sheet[v]);
    const Vec3& p = mesh.vertices[v];
    out << p.x() << ' ' << p.y() << ' ' << p.z() << ' ' << c[0] << ' ' << c[1] << ' ' << c[2] << ' '
        << r.vertex_sheet[v] << ' ' << int(r.vertex_removed[v]) << ' '
        << (r.vertex_node[v] == kNoId ? -1 : static_cast<long long>(r.vertex_node[v])) << '\n';
  }
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto c = label_colour(r.face_sheet[f]);
    const Tri& t = mesh.faces[f];
    out << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << ' ' << c[0] << ' ' << c[1] << ' ' << c[2] << ' '
        << r.face_sheet[f] << '\n';
  }
}

void write_surface_ply(std::ostream& out, const DurixResult& r) {
  const SurfaceMesh& m = r.surface;
  out << "ply\nformat ascii 1.0\ncomment medax durix: the working surface M_w dual to the medial axis\n";
  out << "element vertex " << m.vertices.size()
      << "\nproperty double x\nproperty double y\nproperty double z\nproperty int input_index\n";
  out << "element face " << m.faces.size()
      << "\nproperty list uchar int vertex_indices\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
         "property int node\nproperty int sheet\nend_header\n";
  out.precision(17);
  for (std::size_t v = 0; v < m.vertices.size(); ++v) {
    const Vec3& p = m.vertices[v];
    out << p.x() << ' ' << p.y() << ' ' << p.z() << ' ' << r.surface_vertex[v] << '\n';
  }
  for (std::size_t f = 0; f < m.faces.size(); ++f) {
    const auto c = label_colour(r.surface_face_sheet[f]);
    const Tri& t = m.faces[f];
    out << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << ' ' << c[0] << ' ' << c[1] << ' ' << c[2] << ' '
        << r.surface_face_node[f] << ' ' << r.surface_face_sheet[f] << '\n';
  }
}

}  // namespace medax::durix
