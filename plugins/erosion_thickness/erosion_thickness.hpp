#pragma once
// Erosion Thickness on a MedialComplex: the glue between the data model and the algorithms
// (burn.hpp, medial_curves.hpp, skeleton.hpp). The stages call these; so do the tests and the
// benchmark.
#include "burn.hpp"
#include "medial_curves.hpp"
#include "skeleton.hpp"

#include <medax/medial_complex.hpp>
#include <medax/surface.hpp>

#include <functional>
#include <memory>
#include <string>

namespace medax::et {

/// Reference length L that omega, theta1, theta2, phi1 (× L) and phi2 (× L²) are relative to:
/// "shape_max_side" (longest side of the shape's bounding box; the complex's when the shape has
/// neither mesh nor samples), "complex_max_side", or "absolute" (L = 1).
double reference_length(const Shape& shape, const MedialComplex& medial, const std::string& relative_to);

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
