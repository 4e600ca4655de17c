#include "uncovered_regions.hpp"

#define TETLIBRARY
#include <tetgen.h>

#include <medax/union_find.hpp>

#include <algorithm>
#include <map>
#include <stdexcept>

namespace medax::msd {
namespace {

/// S as a TetGen piecewise linear complex: its vertices and one triangle polygon per face.
void fill_input(const SurfaceMesh& surface, tetgenio& in) {
  in.firstnumber = 0;
  in.numberofpoints = static_cast<int>(surface.vertices.size());
  in.pointlist = new REAL[3 * surface.vertices.size()];
  for (std::size_t v = 0; v < surface.vertices.size(); ++v)
    for (int k = 0; k < 3; ++k) in.pointlist[3 * v + k] = surface.vertices[v][k];
  in.numberoffacets = static_cast<int>(surface.faces.size());
  in.facetlist = new tetgenio::facet[surface.faces.size()];
  for (std::size_t f = 0; f < surface.faces.size(); ++f) {
    tetgenio::facet& facet = in.facetlist[f];
    tetgenio::init(&facet);
    facet.numberofpolygons = 1;
    facet.polygonlist = new tetgenio::polygon[1];
    tetgenio::init(&facet.polygonlist[0]);
    facet.polygonlist[0].numberofvertices = 3;
    facet.polygonlist[0].vertexlist = new int[3];
    for (int k = 0; k < 3; ++k) facet.polygonlist[0].vertexlist[k] = static_cast<int>(surface.faces[f][k]);
  }
}

Vec3 point_of(const tetgenio& out, int index) {
  return {out.pointlist[3 * index], out.pointlist[3 * index + 1], out.pointlist[3 * index + 2]};
}

SolidTets read_output(const tetgenio& out) {
  SolidTets tets;
  const auto count = static_cast<std::size_t>(out.numberoftetrahedra);
  tets.centroids.resize(count);
  tets.volumes.resize(count);
  tets.neighbours.resize(count);
  for (std::size_t t = 0; t < count; ++t) {
    std::array<Vec3, 4> p;
    for (int k = 0; k < 4; ++k) p[k] = point_of(out, out.tetrahedronlist[4 * t + k]);
    tets.centroids[t] = (p[0] + p[1] + p[2] + p[3]) / 4;
    tets.volumes[t] = std::abs((p[1] - p[0]).dot((p[2] - p[0]).cross(p[3] - p[0]))) / 6;
    for (int k = 0; k < 4; ++k) tets.neighbours[t][k] = out.neighborlist[4 * t + k];
  }
  return tets;
}

}  // namespace

SolidTets tetrahedralize_solid(const SurfaceMesh& surface, const std::string& switches) {
  tetgenio in, out;
  fill_input(surface, in);
  std::string all = switches + "Qn";
  try {
    tetrahedralize(all.data(), &in, &out);
  } catch (int code) {
    // TetGen reports errors by throwing its exit code (1 memory, 2 internal, 3 self-intersection, ...).
    throw std::runtime_error("TetGen failed on the surface with switches '" + all + "' (code " +
                             std::to_string(code) + "); repair the mesh (a `repair` stage) or change `tetgen_switches`");
  }
  if (out.numberoftetrahedra == 0 || !out.neighborlist)
    throw std::runtime_error("TetGen produced no tetrahedra for switches '" + all + "'");
  return read_output(out);
}

std::vector<UncoveredRegion> uncovered_regions(const SolidTets& tets, const std::vector<char>& covered) {
  UnionFind groups(tets.size());
  for (std::size_t t = 0; t < tets.size(); ++t) {
    if (covered[t]) continue;
    for (int n : tets.neighbours[t])
      if (n >= 0 && !covered[static_cast<std::size_t>(n)]) groups.unite(static_cast<Index>(t), static_cast<Index>(n));
  }
  std::map<Index, UncoveredRegion> by_root;  // the root is the group's lowest tet
  for (std::size_t t = 0; t < tets.size(); ++t) {
    if (covered[t]) continue;
    UncoveredRegion& region = by_root[groups.find(static_cast<Index>(t))];
    region.volume += tets.volumes[t];
    region.centre += tets.volumes[t] * tets.centroids[t];
    ++region.tets;
  }
  std::vector<UncoveredRegion> regions;
  for (auto& [root, region] : by_root) {
    if (region.volume > 0) region.centre /= region.volume;
    regions.push_back(region);
  }
  std::stable_sort(regions.begin(), regions.end(),
                   [](const UncoveredRegion& a, const UncoveredRegion& b) { return a.volume > b.volume; });
  return regions;
}

}  // namespace medax::msd
