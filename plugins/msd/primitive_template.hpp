#pragma once
// Templates of the generalized enveloping primitives (paper §5.2, Fig. 9; notes §2.5): vertex →
// sphere, edge → cylinder wall + 2 hemispherical caps, triangle → 2 planar copies + 3 half-cylinder
// walls + 3 spherical wedges. Each is built as a stack of closed rings of directions, zipped
// together; the poles of the sphere and capsule are single points and the triangle's planar copies
// are barycentric grids whose boundary is the first and last ring.
#include "primitive.hpp"

#include <cstddef>
#include <vector>

namespace medax::msd {

struct TemplateOptions {
  /// Vertices of the vertex template (paper: 1,588; the rings give 1,617 for it). Sets the angular
  /// step θ = √(4π / n) used by every curved part of every template.
  std::size_t sphere_vertices = 1588;
  /// Cap on the segments along an edge or a triangle side (spacing θ·ρ0 otherwise), which bounds
  /// a template's size for long thin elements.
  std::size_t max_segments = 200;
};

/// The template of `element` at the template radius `radius` (ρ0): spacing along the element is
/// θ·radius, so the template's resolution scales with the element's size relative to ρ0.
/// Throws std::invalid_argument for a degenerate element (coincident corners, collinear triangle).
PrimitiveTemplate make_template(const SkeletonElement& element, double radius, const TemplateOptions& options = {});

/// Unique edges of a face list, each (low, high).
std::vector<Segment> template_edges(const std::vector<Tri>& faces);

}  // namespace medax::msd
