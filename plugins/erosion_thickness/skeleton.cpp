// et_skeleton (Yan et al. 2016, §5): the refined cell complex, protection, contraction, output.
#include "skeleton.hpp"

#include "skeleton_cells.hpp"
#include "skeleton_contraction.hpp"
#include "skeleton_output.hpp"

#include <algorithm>
#include <chrono>

namespace medax::et {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

}  // namespace

Skeleton compute_skeleton(const BurnGraph& g, const Subdivision& sub, const std::vector<Segment>& loose_edges,
                          const SkeletonOptions& options) {
  const auto t0 = Clock::now();
  const std::vector<double> et_c = curve_erosion_thickness(sub);
  Skeleton out;
  const skeleton::CellComplex k = skeleton::build_cell_complex(g, sub, loose_edges, et_c);
  out.refined_faces = k.num_wedges();
  out.refined_edges = k.num_cells();
  out.seconds_refine = seconds_since(t0);

  const auto t1 = Clock::now();
  const skeleton::Kept kept = skeleton::protect(sub, k, options, out);
  out.seconds_protect = seconds_since(t1);

  skeleton::Contraction contraction(k, kept, g.num_vertices(), sub.num_points());
  out.refined_vertices =
      static_cast<std::size_t>(std::count(contraction.v_alive.begin(), contraction.v_alive.end(), 1));
  contraction.run();
  out.seconds_contract = seconds_since(t1);

  const auto t2 = Clock::now();
  skeleton::write_output(g, sub, k, et_c, contraction, options.coarsen, out);
  out.seconds_output = seconds_since(t2);
  return out;
}

}  // namespace medax::et
