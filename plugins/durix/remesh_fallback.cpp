// DZM07, the remesh fallback, and the checks of every result (notes §1.2: "always verify").
#include "remesh_fallback.hpp"

#include <medax/context.hpp>
#include <medax/services/mesh_check.hpp>

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <stdexcept>

namespace medax::durix {

namespace {

struct Topology {
  long long genus = 0;
  std::size_t components = 0;
};

services::MeshReport check_without_self_intersections(const SurfaceMesh& mesh) {
  services::MeshCheckOptions options;
  options.self_intersections = false;  // the caller tested the input; a Delaunay surface cannot self-intersect
  return services::check_mesh(mesh, options);
}

Topology topology_of_input(const SurfaceMesh& mesh) {
  const services::MeshReport report = check_without_self_intersections(mesh);
  if (!report.valid_solid() || !report.genus)
    throw std::runtime_error("the input does not bound a solid: " + report.describe_problems() +
                             "; put a `repair` stage before");
  return {*report.genus, report.components};
}

/// What is wrong with a conversion result, or an empty string when it passes.
std::string result_problems(const SurfaceMesh& out, const Topology& input, bool check_delaunay) {
  const services::MeshReport report = check_without_self_intersections(out);
  if (!report.ok()) return "the result is not a clean closed 2-manifold: " + report.describe_problems();
  if (*report.genus != input.genus || report.components != input.components)
    return fmt::format("the result has genus {} in {} component(s), the input genus {} in {}", *report.genus,
                       report.components, input.genus, input.components);
  if (check_delaunay) {
    const DelaunayCheck check = check_delaunay_mesh(out);
    if (!check.ok()) return "the result does not verify on a fresh tetrahedralization: " + check.describe();
  }
  return {};
}

/// The remesh, retried when an attempt fails: at half the sizes when the result lost a thin part
/// or a handle (or does not verify), at twice the facet distance when the mesher did not finish
/// (its manifold refinement can run away at near-touching sheets and creases; measured on
/// cheese at facet_distance 0.002 of the diagonal, while 0.001 and 0.004 converge).
SurfaceMesh remesh_checked(const SurfaceMesh& mesh, const Topology& input, const DelaunaySurfaceOptions& options,
                           RemeshReport& report, const std::function<void()>& check_cancelled,
                           const std::function<void(const std::string&)>& note) {
  RemeshOptions attempt = options.remesh;
  std::string failures;
  for (int k = 0; k < options.remesh_attempts; ++k) {
    if (check_cancelled) check_cancelled();
    const RemeshOptions tried = attempt;
    if (note)
      note(fmt::format("remesh attempt {} of {}: facet_size {:.3g} × the mean edge length, facet_distance {:.3g} × "
                       "the diagonal",
                       k + 1, options.remesh_attempts, tried.facet_size, tried.facet_distance));
    std::string failure;
    try {
      SurfaceMesh out = remesh_restricted_delaunay(mesh, attempt, &report);
      failure = result_problems(out, input, true);
      if (failure.empty()) return out;
      failure += fmt::format(" (Mesh_3: {} vertices, {} surface facets, {} inside cells)", report.mesh3_vertices,
                             report.restricted_facets, report.inside_cells);
      attempt.facet_size /= 2;
      attempt.facet_distance /= 2;
    } catch (const RemeshRefinementError& e) {
      failure = e.what();
      attempt.facet_distance *= 2;
    }
    if (note) note(fmt::format("remesh attempt {} failed: {}", k + 1, failure));
    failures += fmt::format("{}attempt {} at facet_size {:.3g}, facet_distance {:.3g}: {}", k ? "; " : "", k + 1,
                            tried.facet_size, tried.facet_distance, failure);
  }
  throw std::runtime_error(fmt::format(
      "the remesh failed {} time(s): {}; lower remesh_facet_size (thin parts and handles need triangles smaller "
      "than their thickness) or, when the mesher did not finish, raise remesh_facet_distance; or raise "
      "remesh_attempts",
      options.remesh_attempts, failures));
}

}  // namespace

DelaunaySurfaceResult make_delaunay_surface(const SurfaceMesh& mesh, const DelaunaySurfaceOptions& options,
                                            const std::function<void()>& check_cancelled,
                                            const std::function<void(const std::string&)>& note) {
  const auto t0 = std::chrono::steady_clock::now();
  DelaunaySurfaceResult result;
  const Topology input = topology_of_input(mesh);
  result.genus = input.genus;
  result.components = input.components;
  if (options.method == DelaunayMethod::Dzm07) {
    try {
      // make_delaunay_mesh verifies the Delaunay property itself; the topology is checked here.
      result.mesh = make_delaunay_mesh(mesh, options.dzm07, &result.dzm07, check_cancelled);
      const std::string problems = result_problems(result.mesh, input, false);
      if (!problems.empty()) throw std::runtime_error(problems);
      result.method = DelaunayMethod::Dzm07;
    } catch (const Cancelled&) {
      throw;
    } catch (const std::runtime_error& e) {
      if (options.fallback == DelaunayFallback::None)
        throw std::runtime_error(std::string("DZM07 flips and splits failed: ") + e.what() +
                                 " (fallback: none; set fallback: remesh to resample the surface instead)");
      result.dzm07_failure = e.what();
    }
  }
  if (options.method == DelaunayMethod::Remesh || !result.dzm07_failure.empty()) {
    try {
      result.mesh = remesh_checked(mesh, input, options, result.remesh, check_cancelled, note);
    } catch (const Cancelled&) {
      throw;
    } catch (const std::runtime_error& e) {
      if (result.dzm07_failure.empty()) throw;
      throw std::runtime_error("DZM07 flips and splits failed (" + result.dzm07_failure +
                               "), and so did the remesh fallback: " + e.what());
    }
    result.method = DelaunayMethod::Remesh;
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

}  // namespace medax::durix
