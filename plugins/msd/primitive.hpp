#pragma once
// The generalized enveloping primitive of one skeleton element (paper Def. 4.1, §5.2; notes §2.5,
// §4): a closed triangle mesh whose vertex i sits at b_i + ρ_i d_i, with b_i on the element, d_i a
// unit direction of the element's normal bundle and ρ_i > 0 its radius (notes §9.1: radii are
// measured from the element, not from ∂P^ε).
#include <medax/geometry.hpp>
#include <medax/surface.hpp>

#include <array>
#include <string>
#include <vector>

namespace medax::msd {

/// The three kinds of skeleton element; the value is the number of corners.
enum class ElementKind : int { Vertex = 1, Edge = 2, Triangle = 3 };

/// A skeleton element P = cvx(corners): its skeleton vertex ids and their positions.
struct SkeletonElement {
  ElementKind kind = ElementKind::Vertex;
  std::array<Index, 3> ids{};     ///< the first corner_count() are used
  std::array<Vec3, 3> corners{};  ///< positions of those ids
  int corner_count() const { return static_cast<int>(kind); }
  /// Mean of the corners.
  Vec3 centre() const;
  /// cp(x; P): the point of the element closest to x.
  Vec3 closest_point(const Vec3& x) const;
};

/// The discretised direction set d(P): one template vertex per direction, with its base point on
/// P, and the faces of ∂P^ρ0 (closed, 2-manifold, outward oriented).
struct PrimitiveTemplate {
  std::vector<Vec3> base;       ///< b_i ∈ P
  std::vector<Vec3> direction;  ///< d_i, unit
  std::vector<Tri> faces;
  std::size_t size() const { return base.size(); }
};

/// A fitted primitive T_P. `fitted` is false when the fitting failed (`failure` says why); the
/// radii are then empty.
struct Primitive {
  SkeletonElement element;
  PrimitiveTemplate shape;
  double initial_radius = 0;        ///< ρ0
  std::vector<double> max_radius;   ///< ρmax_i: distance from b_i along d_i to where the ray leaves S
  std::vector<double> radius;       ///< ρ_i ≤ ρmax_i
  int solves = 0;                   ///< sparse solves the fit took (all progressions)
  bool fitted = false;
  std::string failure;
};

/// Vertices b_i + r_i d_i of a template for the radii r (r.size() == shape.size()).
std::vector<Vec3> primitive_vertices(const PrimitiveTemplate& shape, const std::vector<double>& r);
/// T_P as a surface mesh (the fitted radii).
SurfaceMesh primitive_mesh(const Primitive& primitive);

}  // namespace medax::msd
