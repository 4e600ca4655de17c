#pragma once
// The whole `delaunay_surface` conversion: DZM07 flips and splits (delaunay_mesh.hpp), falling
// back to a restricted-Delaunay remesh (remesh.hpp) when they do not converge, and the checks
// every result must pass before it is returned: Delaunay on a fresh tetrahedralization, closed,
// 2-manifold, outward, and the input's genus and component count.
#include "delaunay_mesh.hpp"
#include "remesh.hpp"

#include <functional>
#include <string>

namespace medax::durix {

enum class DelaunayMethod { Dzm07, Remesh };
/// What to do when DZM07 fails.
enum class DelaunayFallback { Remesh, None };

struct DelaunaySurfaceOptions {
  DelaunayMethod method = DelaunayMethod::Dzm07;
  /// When DZM07 fails: remesh instead, or refuse.
  DelaunayFallback fallback = DelaunayFallback::Remesh;
  /// Remesh attempts, each at half the facet size and distance of the one before (a thin part
  /// or a small handle lost by a coarse remesh changes the genus, which is refused).
  int remesh_attempts = 3;
  DelaunayMeshOptions dzm07;
  RemeshOptions remesh;
};

struct DelaunaySurfaceResult {
  SurfaceMesh mesh;
  DelaunayMethod method = DelaunayMethod::Dzm07;  ///< the method that produced `mesh`
  std::string dzm07_failure;  ///< why DZM07 failed when the remesh was used after it, else empty
  DelaunayMeshReport dzm07;
  RemeshReport remesh;
  long long genus = 0;        ///< of the input and of the result (they are checked equal)
  std::size_t components = 0;
  double seconds = 0;         ///< everything, checks included
};

/// Converts `mesh` (closed, manifold, outward, no duplicates; checked by the caller) into a
/// Delaunay mesh by `options.method`, with the remesh fallback for DZM07. Throws
/// std::runtime_error naming what failed and what to do when no method gives a result that
/// passes every check. `note` hears each remesh attempt as it starts and why it failed (a
/// remesh can take a minute).
DelaunaySurfaceResult make_delaunay_surface(const SurfaceMesh& mesh, const DelaunaySurfaceOptions& options = {},
                                            const std::function<void()>& check_cancelled = {},
                                            const std::function<void(const std::string&)>& note = {});

}  // namespace medax::durix
