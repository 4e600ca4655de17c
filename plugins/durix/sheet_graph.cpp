// The sheet graph from the labels of a Durix medial complex.
#include "sheet_graph.hpp"

#include "durix.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <map>
#include <ostream>
#include <set>
#include <stdexcept>

namespace medax::durix {

namespace {

const std::vector<int>& require(const MedialComplex& mc, const Property<int>& label) {
  if (!mc.has(label))
    throw std::invalid_argument(fmt::format("sheet graph: the complex has no {} label '{}' (it is not a durix output)",
                                            label.element == Element::Face ? "face" : "edge", label.name));
  return mc.get(label);
}

std::pair<Index, Index> ordered(Index a, Index b) { return a < b ? std::pair{a, b} : std::pair{b, a}; }

/// The Durix label columns the graph is built from.
struct SheetLabels {
  const std::vector<int>& face_sheet;
  const std::vector<int>& face_polygon;
  const std::vector<int>& path_type;
  const std::vector<int>& edge_sheet;
  explicit SheetLabels(const MedialComplex& mc)
      : face_sheet(require(mc, kFaceSheet)),
        face_polygon(require(mc, kVoronoiFace)),
        path_type(require(mc, kPathType)),
        edge_sheet(require(mc, kEdgeSheet)) {}
};

/// Accumulates the nodes and edges of the graph, one kind of element at a time.
struct GraphBuilder {
  const MedialComplex& mc;
  const SheetLabels& labels;
  SheetGraph graph;
  std::vector<std::set<int>> vertex_sheets;
  std::map<std::pair<Index, Index>, std::set<int>> side_sheets;  ///< the sheets of the faces at a medial edge
  std::map<std::pair<int, int>, SheetAdjacency> adjacency;

  GraphBuilder(const MedialComplex& complex, const SheetLabels& l) : mc(complex), labels(l) {
    vertex_sheets.resize(mc.num_vertices());
    int count = 0;
    for (int s : labels.face_sheet) count = std::max(count, s + 1);
    for (std::size_t e = 0; e < mc.edges.size(); ++e)
      if (labels.path_type[e] == kCurve) count = std::max(count, labels.edge_sheet[e] + 1);
    graph.sheets.resize(static_cast<std::size_t>(count));
    for (int s = 0; s < count; ++s) graph.sheets[s].id = s;
  }

  /// Sheet areas and polygon counts; the sheets at each vertex and each face side.
  void add_faces() {
    std::set<int> polygons_seen;
    for (std::size_t f = 0; f < mc.faces.size(); ++f) {
      const int s = labels.face_sheet[f];
      if (s < 0) continue;
      const auto& t = mc.faces[f];
      SheetNode& node = graph.sheets[s];
      node.area += 0.5 * (mc.centres[t[1]] - mc.centres[t[0]]).cross(mc.centres[t[2]] - mc.centres[t[0]]).norm();
      if (polygons_seen.insert(labels.face_polygon[f]).second) ++node.polygons;
      for (int i = 0; i < 3; ++i) {
        vertex_sheets[t[i]].insert(s);
        side_sheets[ordered(t[i], t[(i + 1) % 3])].insert(s);
      }
    }
  }

  /// Curve lengths, boundary edge counts, and the singular edges each pair of sheets shares.
  void add_edges() {
    for (std::size_t e = 0; e < mc.edges.size(); ++e) {
      const auto& [u, v] = mc.edges[e];
      const int sheet = labels.edge_sheet[e];
      switch (labels.path_type[e]) {
        case kCurve:
          graph.sheets[sheet].curve = true;
          graph.sheets[sheet].length += (mc.centres[u] - mc.centres[v]).norm();
          vertex_sheets[u].insert(sheet);
          vertex_sheets[v].insert(sheet);
          break;
        case kBoundary:
          if (sheet >= 0) ++graph.sheets[sheet].boundary_edges;
          break;
        case kSingular:
        case kForcedSingular:
          if (const auto it = side_sheets.find(ordered(u, v)); it != side_sheets.end())
            for_each_pair(it->second, [&](int a, int b) { ++adjacency[{a, b}].singular_edges; });
          break;
        default: break;
      }
    }
  }

  /// Vertex counts per sheet, and the vertices each pair of sheets shares.
  void add_shared_vertices() {
    for (const std::set<int>& sheets : vertex_sheets) {
      for (int s : sheets) ++graph.sheets[s].medial_vertices;
      for_each_pair(sheets, [&](int a, int b) { ++adjacency[{a, b}].shared_vertices; });
    }
  }

  SheetGraph finish() {
    for (auto& [key, adj] : adjacency) {
      adj.a = key.first;
      adj.b = key.second;
      graph.adjacency.push_back(adj);
    }
    return std::move(graph);
  }

  template <typename F>
  static void for_each_pair(const std::set<int>& sheets, const F& f) {
    for (auto a = sheets.begin(); a != sheets.end(); ++a)
      for (auto b = std::next(a); b != sheets.end(); ++b) f(*a, *b);
  }
};

}  // namespace

SheetGraph sheet_graph(const MedialComplex& mc) {
  const SheetLabels labels(mc);
  GraphBuilder builder(mc, labels);
  builder.add_faces();
  builder.add_edges();
  builder.add_shared_vertices();
  return builder.finish();
}

void write_sheet_graph_json(std::ostream& out, const SheetGraph& graph) {
  const double scale = graph.input_scale;
  nlohmann::ordered_json sheets = nlohmann::ordered_json::array(), adjacency = nlohmann::ordered_json::array();
  for (const SheetNode& s : graph.sheets)
    sheets.push_back({{"id", s.id},
                      {"kind", s.curve ? "curve" : "sheet"},
                      {"polygons", s.polygons},
                      {"area", s.area * scale * scale},
                      {"length", s.length * scale},
                      {"boundary_edges", s.boundary_edges},
                      {"medial_vertices", s.medial_vertices}});
  for (const SheetAdjacency& a : graph.adjacency)
    adjacency.push_back({{"a", a.a},
                         {"b", a.b},
                         {"via", a.singular_edges > 0 ? "singular path" : "vertex"},
                         {"singular_edges", a.singular_edges},
                         {"shared_vertices", a.shared_vertices}});
  out << nlohmann::ordered_json{{"sheets", sheets}, {"adjacency", adjacency}}.dump(1) << '\n';
}

}  // namespace medax::durix
