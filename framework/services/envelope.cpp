// The envelope of a medial complex (medax/services/envelope.hpp): its maximal elements become
// primitives, whose closed-form distances (envelope_primitives.hpp) a bounding-volume hierarchy
// searches (envelope_bvh.hpp); boundary points come from envelope_sampling.cpp.
#include <medax/services/envelope.hpp>

#include "envelope_bvh.hpp"
#include "envelope_sampling.hpp"

#include <medax/services/kdtree.hpp>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

namespace medax::services {

using envelope_detail::EnvelopeBvh;
using envelope_detail::Eval;
using envelope_detail::Hit;
using envelope_detail::kInf;
using envelope_detail::PrimGeom;

struct Envelope::Impl {
  std::vector<EnvelopePrimitive> primitives;  // public order
  EnvelopeBvh bvh;
};

namespace {

/// Throws unless every element's vertex exists and centres and radii are as many.
void check_indices(const MedialComplex& medial) {
  const std::size_t nv = medial.num_vertices();
  if (medial.radii.size() != nv)
    throw std::invalid_argument("envelope: the medial complex has " + std::to_string(nv) + " centres but " +
                                std::to_string(medial.radii.size()) + " radii");
  const auto check = [nv](Index v, const char* kind, std::size_t i) {
    if (v >= nv)
      throw std::invalid_argument(std::string("envelope: ") + kind + " " + std::to_string(i) +
                                  " refers to vertex " + std::to_string(v) + " of " + std::to_string(nv));
  };
  for (std::size_t f = 0; f < medial.faces.size(); ++f)
    for (Index v : medial.faces[f]) check(v, "face", f);
  for (std::size_t e = 0; e < medial.edges.size(); ++e)
    for (Index v : medial.edges[e]) check(v, "edge", e);
}

/// The maximal elements: distinct non-degenerate triangles; edges (explicit ones and degenerate
/// triangles) that are no triangle's side; vertices in no edge or triangle. In that order:
/// vertices, then segments and triangles by sorted vertex indices.
std::vector<EnvelopePrimitive> maximal_primitives(const MedialComplex& medial) {
  const std::size_t nv = medial.num_vertices();
  using Key3 = std::array<Index, 3>;
  std::vector<std::pair<Key3, Index>> tris;
  std::vector<std::pair<std::array<Index, 2>, std::pair<Element, Index>>> segs;
  std::vector<char> covered(nv, 0);
  for (std::size_t f = 0; f < medial.faces.size(); ++f) {
    Key3 k = medial.faces[f];
    std::sort(k.begin(), k.end());
    if (k[0] != k[1] && k[1] != k[2]) {
      tris.push_back({k, static_cast<Index>(f)});
    } else if (k[0] != k[2]) {
      segs.push_back({{k[0], k[2]}, {Element::Face, static_cast<Index>(f)}});
    }
    for (Index v : k) covered[v] = 1;
  }
  for (std::size_t e = 0; e < medial.edges.size(); ++e) {
    const Segment& s = medial.edges[e];
    if (s[0] != s[1]) {
      segs.push_back({{std::min(s[0], s[1]), std::max(s[0], s[1])}, {Element::Edge, static_cast<Index>(e)}});
      covered[s[0]] = covered[s[1]] = 1;
    }
  }
  std::stable_sort(tris.begin(), tris.end(), [](const auto& p, const auto& q) { return p.first < q.first; });
  tris.erase(std::unique(tris.begin(), tris.end(), [](const auto& p, const auto& q) { return p.first == q.first; }),
             tris.end());
  std::vector<std::array<Index, 2>> sides;
  sides.reserve(3 * tris.size());
  for (const auto& [k, f] : tris) sides.insert(sides.end(), {{k[0], k[1]}, {k[1], k[2]}, {k[0], k[2]}});
  std::sort(sides.begin(), sides.end());
  std::stable_sort(segs.begin(), segs.end(), [](const auto& p, const auto& q) { return p.first < q.first; });
  segs.erase(std::unique(segs.begin(), segs.end(), [](const auto& p, const auto& q) { return p.first == q.first; }),
             segs.end());

  std::vector<EnvelopePrimitive> prims;
  for (Index v = 0; v < nv; ++v)
    if (!covered[v]) prims.push_back({1, {v, v, v}, Element::Vertex, v});
  for (const auto& [k, origin] : segs)
    if (!std::binary_search(sides.begin(), sides.end(), k))
      prims.push_back({2, {k[0], k[1], k[1]}, origin.first, origin.second});
  for (const auto& [k, f] : tris) prims.push_back({3, k, Element::Face, f});
  return prims;
}

/// The balls of each primitive, in the same order. Throws on a non-finite centre or an invalid
/// radius.
std::vector<PrimGeom> primitive_geometry(const MedialComplex& medial, const std::vector<EnvelopePrimitive>& prims) {
  if (prims.size() > std::numeric_limits<std::uint32_t>::max() / 2)
    throw std::invalid_argument("envelope: too many primitives");
  for (const EnvelopePrimitive& p : prims)
    for (int k = 0; k < p.count; ++k) {
      const Index v = p.vertices[k];
      if (!medial.centres[v].allFinite() || !std::isfinite(medial.radii[v]) || medial.radii[v] < 0)
        throw std::invalid_argument("envelope: vertex " + std::to_string(v) + " has a non-finite centre or an "
                                    "invalid radius");
    }
  std::vector<PrimGeom> geometry(prims.size());
  tbb::parallel_for(std::size_t{0}, prims.size(), [&](std::size_t i) {
    const EnvelopePrimitive& p = prims[i];
    std::array<Vec3, 3> c;
    std::array<double, 3> r;
    for (int k = 0; k < 3; ++k) {
      const Index v = p.vertices[std::min(k, p.count - 1)];
      c[k] = medial.centres[v];
      r[k] = medial.radii[v];
    }
    geometry[i] = envelope_detail::make_prim(p.count, c, r);
  });
  return geometry;
}

}  // namespace

Envelope::Envelope(const MedialComplex& medial) : impl_(std::make_unique<Impl>()) {
  check_indices(medial);
  impl_->primitives = maximal_primitives(medial);
  impl_->bvh = EnvelopeBvh(primitive_geometry(medial, impl_->primitives));
}

Envelope::~Envelope() = default;
Envelope::Envelope(Envelope&&) noexcept = default;
Envelope& Envelope::operator=(Envelope&&) noexcept = default;

const std::vector<EnvelopePrimitive>& Envelope::primitives() const { return impl_->primitives; }

std::pair<Vec3, Vec3> Envelope::bounds() const { return {impl_->bvh.bounds().lo, impl_->bvh.bounds().hi}; }

double Envelope::signed_distance(const Vec3& x) const { return impl_->bvh.query(x).d; }

EnvelopeHit Envelope::closest(const Vec3& x) const {
  const Hit h = impl_->bvh.query(x);
  EnvelopeHit hit;
  hit.distance = h.d;
  if (h.prim >= 0) {
    const Eval e = impl_->bvh.ball(x, h.prim);
    hit.centre = e.c;
    hit.radius = e.r;
    hit.primitive = impl_->bvh.public_index(h.prim);
  }
  return hit;
}

std::vector<double> Envelope::signed_distances(const std::vector<Vec3>& points) const {
  std::vector<double> out(points.size());
  tbb::parallel_for(std::size_t{0}, points.size(), [&](std::size_t i) { out[i] = signed_distance(points[i]); });
  return out;
}

double Envelope::signed_distance_brute_force(const Vec3& x) const {
  double best = kInf;
  for (const PrimGeom& g : impl_->bvh.geometry()) best = std::min(best, g.value(x));
  return best;
}

EnvelopeSamples Envelope::sample_boundary(double step, const std::function<void(double)>& progress,
                                          const CancelCheck& cancel) const {
  return envelope_detail::sample_boundary(impl_->bvh, step, progress, envelope_detail::CancelPoll(cancel));
}

namespace {

/// Inside points whose distance to ∂E is only bounded by the nearest boundary sample.
struct Uncertified {
  std::vector<std::size_t> index;  ///< into the points
  std::vector<double> depth;       ///< −φ: the lower bound
  std::vector<std::int64_t> prim;  ///< the deepest primitive (BVH order)
};

/// How far the refinement looks between the lower bound (depth) and the samples' upper bound: on
/// Voronoi envelopes the nearest boundary point is close to the depth (spot: a quarter of the way
/// gives the ε̄¹ of looking all the way, to 6 digits, at half the cost).
constexpr double kRefineShare = 0.25;
/// Grid points a refined point may cost at most (a point deep inside a large primitive would
/// need a large shell); beyond, it keeps the samples' bound.
constexpr double kMaxShellPoints = 4096;

/// Tightens the upper bounds out[i] of the uncertified points with the boundary points sampled at
/// `step` (finer than the samples) within depth + kRefineShare·(out[i] − depth) + step of each:
/// every such point lies on ∂E, so the distance to the nearest stays an upper bound. The grid
/// points closer than depth − step are inside E with all their neighbours (φ is 1-Lipschitz), so
/// no crossing edge needs them: only a shell is searched.
void refine_uncertified(const EnvelopeBvh& bvh, const std::vector<Vec3>& points, const Uncertified& open,
                        double step, std::vector<double>& out, const envelope_detail::CancelPoll& poll) {
  std::vector<Vec3> centres;
  std::vector<double> inner, outer;
  std::vector<std::int64_t> seeds;
  std::vector<std::size_t> refined;  // into open
  for (std::size_t u = 0; u < open.index.size(); ++u) {
    const double r0 = open.depth[u] - step;
    const double r1 = open.depth[u] + kRefineShare * (out[open.index[u]] - open.depth[u]) + step;
    const double volume = 4.0 / 3.0 * M_PI * (r1 * r1 * r1 - std::pow(std::max(0.0, r0), 3));
    if (volume > kMaxShellPoints * step * step * step) continue;
    refined.push_back(u);
    centres.push_back(points[open.index[u]]);
    inner.push_back(r0);
    outer.push_back(r1);
    seeds.push_back(open.prim[u]);
  }
  std::vector<Vec3> near;
  try {
    near = envelope_detail::sample_boundary_near(bvh, step, centres, inner, outer, seeds, poll);
  } catch (const std::invalid_argument&) {
    return;  // a step too fine for the grid's keys: keep the samples' bounds
  }
  if (near.empty()) return;
  const PointIndex index(near);
  for (std::size_t c = 0; c < refined.size(); ++c) {
    const std::size_t u = refined[c];
    double& d = out[open.index[u]];
    d = std::max(open.depth[u], std::min(d, index.nearest(centres[c]).second));
  }
}

/// The deepest primitive at x, the search seeded with the primitive under the nearest boundary
/// sample when the samples carry their primitives.
Hit seeded_query(const EnvelopeBvh& bvh, const Vec3& x, const PointIndex* index, const EnvelopeSamples& samples) {
  Hit start{kInf, -1};
  if (index && samples.primitives.size() == samples.points.size()) {
    const Index p = samples.primitives[index->nearest(x).first];
    if (p < bvh.bvh_index().size()) {
      const std::int64_t b = bvh.bvh_index()[p];
      start = {bvh.primitive(b).value(x), b};
    }
  }
  return bvh.query(x, kInf, -kInf, -kInf, start);
}

/// Inside E: true when the closest point of the deepest primitive's ball lies on no other
/// primitive, so that the depth −φ(x) is exactly the distance to ∂E.
bool depth_is_exact(const EnvelopeBvh& bvh, const Vec3& x, const Hit& hit, double tolerance) {
  const Eval ball = bvh.ball(x, hit.prim);
  const Vec3 away = x - ball.c;
  const double len = away.norm();
  if (!(len > 0 || ball.r == 0)) return false;
  const Vec3 q = len > 0 ? Vec3(ball.c + ball.r * away / len) : ball.c;
  return bvh.query(q, tolerance, -tolerance, tolerance, {0.0, hit.prim}).d >= -tolerance;
}

Uncertified collect_uncertified(const std::vector<Hit>& uncertified) {
  Uncertified open;
  for (std::size_t i = 0; i < uncertified.size(); ++i)
    if (uncertified[i].prim >= 0) {
      open.index.push_back(i);
      open.depth.push_back(uncertified[i].d);
      open.prim.push_back(uncertified[i].prim);
    }
  return open;
}

}  // namespace

std::vector<double> Envelope::boundary_distances(const std::vector<Vec3>& points, const EnvelopeSamples& samples,
                                                 std::vector<double>* signed_distances_out,
                                                 const CancelCheck& cancel, double refine_step) const {
  std::vector<double> out(points.size());
  if (signed_distances_out) signed_distances_out->assign(points.size(), kInf);
  if (empty()) {
    std::fill(out.begin(), out.end(), kInf);
    return out;
  }
  // Inside E the depth D into the union satisfies −φ(x) ≤ D. The closest point q of ∂P for the
  // deepest primitive P is at distance −φ(x); when no other primitive covers q, q is on ∂E and
  // D = −φ(x) exactly. Otherwise D ≤ the distance to the nearest boundary sample.
  const EnvelopeBvh& bvh = impl_->bvh;
  const auto [lo, hi] = bounds();
  const double tolerance = 1e-9 * (hi - lo).norm();
  std::unique_ptr<PointIndex> index;
  if (!samples.points.empty()) index = std::make_unique<PointIndex>(samples.points);
  const envelope_detail::CancelPoll poll(cancel);
  std::vector<Hit> uncertified(points.size(), Hit{-1, -1});  // depth and deepest primitive; −1: exact
  tbb::parallel_for(std::size_t{0}, points.size(), [&](std::size_t i) {
    poll.at(i);
    const Vec3& x = points[i];
    const Hit hit = seeded_query(bvh, x, index.get(), samples);
    if (signed_distances_out) (*signed_distances_out)[i] = hit.d;
    const double depth = -hit.d;
    if (hit.d >= 0 || depth_is_exact(bvh, x, hit, tolerance)) {
      out[i] = hit.d >= 0 ? hit.d : depth;
      return;
    }
    out[i] = index ? std::max(depth, index->nearest(x).second) : depth;
    uncertified[i] = {depth, hit.prim};
  });
  // The local grid is at most kMaxRefinement times finer than the samples' (bounded cost).
  constexpr double kMaxRefinement = 4;
  const double step = std::max(refine_step, samples.step / kMaxRefinement);
  if (refine_step > 0 && index && step < samples.step)
    refine_uncertified(bvh, points, collect_uncertified(uncertified), step, out, poll);
  return out;
}

}  // namespace medax::services
