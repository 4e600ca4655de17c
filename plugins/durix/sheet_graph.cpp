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

}  // namespace

SheetGraph sheet_graph(const MedialComplex& mc) {
  const auto& face_sheet = require(mc, kFaceSheet);
  const auto& face_polygon = require(mc, kVoronoiFace);
  const auto& path_type = require(mc, kPathType);
  const auto& edge_sheet = require(mc, kEdgeSheet);

  int count = 0;
  for (int s : face_sheet) count = std::max(count, s + 1);
  for (std::size_t e = 0; e < mc.edges.size(); ++e)
    if (path_type[e] == kCurve) count = std::max(count, edge_sheet[e] + 1);
  SheetGraph graph;
  graph.sheets.resize(static_cast<std::size_t>(count));
  for (int s = 0; s < count; ++s) graph.sheets[s].id = s;

  std::vector<std::set<int>> vertex_sheets(mc.num_vertices());
  // The sheets on each side of a medial edge: the faces that have it as a side.
  std::map<std::pair<Index, Index>, std::set<int>> side_sheets;
  std::set<int> polygons_seen;
  for (std::size_t f = 0; f < mc.faces.size(); ++f) {
    const int s = face_sheet[f];
    if (s < 0) continue;
    const auto& t = mc.faces[f];
    SheetNode& node = graph.sheets[s];
    node.area += 0.5 * (mc.centres[t[1]] - mc.centres[t[0]]).cross(mc.centres[t[2]] - mc.centres[t[0]]).norm();
    if (polygons_seen.insert(face_polygon[f]).second) ++node.polygons;
    for (int i = 0; i < 3; ++i) {
      vertex_sheets[t[i]].insert(s);
      side_sheets[ordered(t[i], t[(i + 1) % 3])].insert(s);
    }
  }
  std::map<std::pair<int, int>, SheetAdjacency> adjacency;
  for (std::size_t e = 0; e < mc.edges.size(); ++e) {
    const auto& [u, v] = mc.edges[e];
    switch (path_type[e]) {
      case kCurve: {
        SheetNode& node = graph.sheets[edge_sheet[e]];
        node.curve = true;
        node.length += (mc.centres[u] - mc.centres[v]).norm();
        vertex_sheets[u].insert(edge_sheet[e]);
        vertex_sheets[v].insert(edge_sheet[e]);
        break;
      }
      case kBoundary:
        if (edge_sheet[e] >= 0) ++graph.sheets[edge_sheet[e]].boundary_edges;
        break;
      case kSingular:
      case kForcedSingular: {
        const auto it = side_sheets.find(ordered(u, v));
        if (it == side_sheets.end()) break;
        for (auto a = it->second.begin(); a != it->second.end(); ++a)
          for (auto b = std::next(a); b != it->second.end(); ++b) ++adjacency[{*a, *b}].singular_edges;
        break;
      }
      default: break;
    }
  }
  for (const std::set<int>& sheets : vertex_sheets) {
    for (int s : sheets) ++graph.sheets[s].medial_vertices;
    for (auto a = sheets.begin(); a != sheets.end(); ++a)
      for (auto b = std::next(a); b != sheets.end(); ++b) ++adjacency[{*a, *b}].shared_vertices;
  }
  for (auto& [key, adj] : adjacency) {
    adj.a = key.first;
    adj.b = key.second;
    graph.adjacency.push_back(adj);
  }
  return graph;
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
