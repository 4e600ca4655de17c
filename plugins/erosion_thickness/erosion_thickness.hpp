#pragma once
// Erosion Thickness on a MedialComplex: the glue between the data model and the algorithms
// (burn.hpp, medial_curves.hpp, skeleton.hpp). The stages call these; so do the tests and the
// benchmark. Also the burn that `erosion_thickness` publishes for `et_medial_curves` and
// `et_skeleton` (one burn feeds the later stages), and the columns the package writes.
#include "burn.hpp"
#include "medial_curves.hpp"
#include "skeleton.hpp"

#include <medax/medial_complex.hpp>
#include <medax/properties.hpp>
#include <medax/scene_data.hpp>
#include <medax/surface.hpp>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace medax::et {

// ---- columns -----------------------------------------------------------------------------------

inline const Property<double> kBt{Element::Vertex, "bt", 1};          ///< burn time (erosion_thickness, et_skeleton)
inline const Property<double> kEt{Element::Vertex, "et", 1};          ///< ET = BT - R
inline const Property<double> kFaceEt{Element::Face, "et", 1};        ///< mean ET of the corners / the wedge priority
inline const Property<double> kBtM{Element::Vertex, "bt_m", 1};       ///< BT of the medial axis at a curve vertex
inline const Property<double> kBtC{Element::Vertex, "bt_c", 1};       ///< BT of the 1D burn on the curves
inline const Property<double> kEtC{Element::Vertex, "et_c", 1};       ///< ET_C = BT_C - BT_M
inline const Property<double> kEdgeEtC{Element::Edge, "et_c", 1};     ///< mean ET_C of the edge's ends
inline const Property<int> kCurveKind{Element::Vertex, "curve_kind"};  ///< what a curve vertex is dual to
inline const Property<int> kEtPoint{Element::Vertex, "et_point"};      ///< what a skeleton point is
inline const Property<int> kMedialCurve{Element::Edge, "medial_curve"};  ///< 1 on the medial curves

// ---- reference length and burn options -----------------------------------------------------------

/// What omega and et_skeleton's thresholds are relative to.
enum class RelativeTo { ShapeMaxSide, ComplexMaxSide, Absolute };
inline const std::vector<std::pair<std::string, RelativeTo>> kRelativeToChoices = {
    {"shape_max_side", RelativeTo::ShapeMaxSide},
    {"complex_max_side", RelativeTo::ComplexMaxSide},
    {"absolute", RelativeTo::Absolute}};

/// Reference length L that omega, theta1, theta2, phi1 (× L) and phi2 (× L²) are relative to:
/// ShapeMaxSide (longest side of the shape's bounding box; the complex's when the shape has
/// neither mesh nor samples), ComplexMaxSide, or Absolute (L = 1).
double reference_length(const Shape& shape, const MedialComplex& medial, RelativeTo relative_to);

/// How a burn is made: the `erosion_thickness` stage's parameters.
struct BurnOptions {
  double omega = 0.004;  ///< largest spacing of graph nodes on an edge, × the reference length
  int min_samples = 1;   ///< least samples per edge
  RelativeTo relative_to = RelativeTo::ShapeMaxSide;
};

// ---- one burn ------------------------------------------------------------------------------------

/// One run of Burn on a complex's triangles. Heap-allocated so that the graph's pointer to the
/// complex stays valid.
struct EtRun {
  TriangleComplex complex;
  BurnGraph graph;
  BurnResult burn;
  std::vector<Segment> loose_edges;  ///< listed edges that bound no triangle
  double seconds_graph = 0, seconds_burn = 0;
};

/// Builds G (absolute `omega`) on every vertex and triangle of `medial` and burns it.
std::unique_ptr<EtRun> run_erosion_thickness(const MedialComplex& medial, double omega, int min_samples,
                                             const std::function<void()>& cancel = {});

/// A cheap identity of a complex: its counts and a hash of its centres, radii, edges and faces
/// (not of its fields: adding ET fields leaves it unchanged).
struct ComplexFingerprint {
  std::size_t vertices = 0, edges = 0, faces = 0;
  std::uint64_t hash = 0;
  bool operator==(const ComplexFingerprint& o) const {
    return vertices == o.vertices && edges == o.edges && faces == o.faces && hash == o.hash;
  }
  bool operator!=(const ComplexFingerprint& o) const { return !(*this == o); }
};
ComplexFingerprint fingerprint(const MedialComplex& medial);
/// "V 5225 E 14579 F 9355".
std::string to_string(const ComplexFingerprint& f);

/// The burn `erosion_thickness` publishes: `et_medial_curves` and `et_skeleton` read it instead of
/// burning again, so they take omega, min_samples and the reference length from it.
struct SharedBurn {
  std::shared_ptr<const EtRun> run;
  BurnOptions options;         ///< what it was made with (omega relative to `length`)
  double length = 1;           ///< the reference length L it used
  ComplexFingerprint complex;  ///< the complex it burned; a later stage refuses any other
};
inline const DataKey<SharedBurn> kBurnData{"et.burn", "erosion_thickness", {}, {}};

/// What a stage of this package that replaced the complex (pure_complex, et_medial_curves,
/// et_skeleton) left behind: a stale burn then names that stage (the publisher).
inline const DataKey<ComplexFingerprint> kReplacedComplex{"et.replaced_complex", "pure_complex", {}, {}};

// ---- storing results in the complex -----------------------------------------------------------

/// Writes vertex fields `bt` and `et` (the graph values at the complex's vertices; +inf on
/// closed surfaces) and face field `et` (mean of its three vertices, for thresholded displays).
void store_erosion_thickness(const EtRun& run, MedialComplex& medial);

/// Replaces `medial` by its medial curves (and the closed surfaces that never burn, as
/// triangles). Vertex fields bt_m, bt_c, et_c, label curve_kind; edge field et_c.
void store_medial_curves(const MedialCurves& curves, MedialComplex& medial);

/// Replaces `medial` by the skeleton. Vertex fields bt, et, et_c, label et_point; edge label
/// medial_curve, edge field et_c; face field et.
void store_skeleton(const Skeleton& skeleton, MedialComplex& medial);

}  // namespace medax::et
