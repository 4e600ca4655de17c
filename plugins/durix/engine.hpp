#pragma once
// Internal: the state of one Durix run, shared by the algorithm files
//   sheets.cpp       sheet labelling and singular path following (§3.3, §3.4)
//   carve.cpp        region flood, ε test, carving and hole closing (§3.5, §3.6)
//   propagation.cpp  the main loop, boundary simplification and the fixpoint (§3.7)
//   problematic.cpp  splitting at problematic edges (§3.8)
//   output.cpp       the medial complex, M_w and the segmentation (§1.4)
#include "dual.hpp"
#include "durix.hpp"

#include <algorithm>
#include <deque>
#include <map>
#include <optional>
#include <unordered_set>
#include <vector>

namespace medax::durix {

/// A followed singular half-path: closed when `closed`.
struct HalfPath {
  std::vector<HalfEdge> edges;
  bool closed = false;
  /// The induced surface loop: the corners met along the walk (paper §3.4.1).
  std::vector<Index> corners;
  /// Corner changes that did not cross a surface edge of M_w (must stay 0).
  std::size_t corner_errors = 0;
};

/// Sorts v and drops repeats.
template <typename T>
void sort_unique(std::vector<T>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

enum class CarveOutcome { Removed, Significant, NotSeparated, NonManifold, TopologyChange };

class Engine {
 public:
  Engine(Dual& dual, const RegionOracle& oracle, const DurixOptions& options, DurixReport& report,
         const CancelFn& check_cancelled);

  /// The fixpoint of passes, then §3.8.
  void run(const ProgressFn& progress);

  // --- sheets.cpp ---------------------------------------------------------------------------
  /// Labels the sheet of face e0 with `label` (flood across regular, non-forced edges); pushes
  /// the half-edges of its faces on singular (degree ≥ 3 or forced) edges onto `queue`.
  std::size_t label_sheet(EdgeId e0, int label, std::deque<HalfEdge>* queue);
  /// A half-edge on a medial edge of degree ≥ 3 (or forced) separating its face from the
  /// neighbouring face on the same side (different or no label).
  bool singular(const HalfEdge& h) const;
  /// Follows the singular half-path through h0 (notes §3.4, Algorithm 2 corrected).
  HalfPath follow(const HalfEdge& h0) const;
  /// Boundary half-edges (degree 1) and their path: the same walk with `boundary` edges.
  HalfPath follow_boundary(const HalfEdge& h0) const;
  bool boundary_half_edge(const HalfEdge& h) const;
  /// Follows every singular and boundary half-path of the final labelling and records the
  /// checks of notes §5.5 in the report.
  void census_paths();

  // --- carve.cpp ----------------------------------------------------------------------------
  /// Tests the region of solid cells reached from `seeds` without entering `path_nodes` (sorted)
  /// and carves it out of the solid when every vertex is covered within ε by the path's balls.
  /// With `stop_at_labels`, a region touching a labelled face is not separated by the path.
  /// Without `test_coverage`, the ε test is skipped (only for carvings that remove no vertex).
  CarveOutcome carve(const std::vector<CellId>& path_nodes, const std::vector<CellId>& seeds, bool stop_at_labels,
                     bool test_coverage = true);
  /// Nodes (cells) of a path.
  std::vector<CellId> path_nodes(const HalfPath& path) const;
  /// The marks of one carving: the path's cells, the flooded region, the vertices seen.
  struct CarveStamps {
    std::uint32_t path = 0, region = 0, vertex = 0;
  };
  struct FloodRules {
    bool stop_at_labels;
    bool test_coverage;
  };
  std::vector<Ball> mark_path(const std::vector<CellId>& path, CarveStamps& stamps);
  /// Floods `region` from the seeds; returns why it stopped early, or nothing when the whole
  /// region is covered and separated from the labelled faces.
  std::optional<CarveOutcome> flood_region(const std::vector<CellId>& seeds, const std::vector<Ball>& balls,
                                           const CarveStamps& stamps, const FloodRules& rules,
                                           std::vector<CellId>& region);
  void reattach_witnesses(const std::vector<CellId>& path, const std::vector<Ball>& balls,
                          const std::vector<CellId>& region, const std::vector<Index>& verts);
  void set_region_solid(const std::vector<CellId>& region, bool solid);

  // --- propagation.cpp ----------------------------------------------------------------------
  /// One pass: labels from a fresh seed per component, carving insignificant sheets. Returns
  /// the number of regions removed.
  std::size_t pass();
  /// Passes until one carves nothing (at most options.max_passes).
  void run_passes(const ProgressFn& progress);
  std::size_t propagate(EdgeId seed);
  /// The ε test and carving of the sheet across a closed singular path from face fx (its
  /// half-edges are marked done); true when the sheet was carved away.
  bool carve_beyond(const HalfPath& path, EdgeId fx, std::unordered_set<HalfEdge, HalfEdgeHash>& done);
  /// After a carving, the path's edges that became regular let the labelled sheet grow into the
  /// unlabelled one across them.
  void grow_across_path(const HalfPath& path, std::deque<HalfEdge>& queue);
  std::size_t simplify_boundaries();
  /// Carves the ends of curves (nodes with three surface facets) covered within ε.
  std::size_t prune_leaves();
  // --- irregular_cells.cpp (Appendix A) -----------------------------------------------------
  /// Flat cells (four cocircular corners) with two surface facets carry no ball; removing one
  /// flips the surface diagonal of a planar quad, which moves no vertex.
  std::size_t peel_flat_cells();
  /// Clusters of cells whose circumcentre lies outside the input, reaching the surface, carved
  /// into the cells around them when the ε test and the manifold (and topology) checks allow it.
  std::size_t remove_outside_centres();
  EdgeId choose_seed(int component) const;

  // --- problematic.cpp ----------------------------------------------------------------------
  void split_problematic();
  bool problematic(const Facet& f) const;
  std::vector<Facet> problematic_edges() const;
  /// Relabels the sheets `labels` (each may fall apart after forcing edges): one scan of the faces.
  void relabel_sheets(const std::vector<int>& labels);
  /// Extends chains of problematic edges from their free ends to their sheet's boundary (rounds
  /// until no progress); returns the problematic edges left.
  std::vector<Facet> cut_chains(std::vector<Facet> found);
  /// Forces the shortest path (Dijkstra on centre distances over the sheet's regular edges)
  /// from `start` to the nearest boundary node of sheet `label`; false when none is reached.
  bool cut_to_sheet_boundary(CellId start, int label);
  /// Splits the fins of the remaining problematic edges (rounds); returns those left.
  std::vector<Facet> split_fins(std::vector<Facet> found);
  /// Per-face scratch of split_fin, reused across calls (stamped, so nothing is cleared).
  struct FinScratch {
    std::vector<std::uint32_t> stamp;
    std::vector<double> best;
    std::vector<char> settled;
    std::vector<Vec3> centroid;  ///< NaN until computed; faces do not change during §4.7
    std::uint32_t current = 0;
    std::vector<CellId> ring;
    std::vector<Facet> facets;
    /// Sizes the scratch for the complex and starts a new call's stamp.
    void prepare(std::size_t num_edges);
  };
  /// Cuts the fin of a problematic edge off its sheet (forced edges, a new label).
  void split_fin(const Facet& edge, FinScratch& scratch);
  /// The faces the fin's front reaches before the other two faces' fronts.
  std::vector<EdgeId> fin_region(const EdgeId faces[3], int fin, FinScratch& scratch) const;
  const Vec3& face_centroid(EdgeId f, FinScratch& scratch) const;
  /// The other face across a regular edge of the sheet, or kNoId.
  EdgeId face_across(const Facet& t, EdgeId f) const;

  // --- state --------------------------------------------------------------------------------
  Dual& d;
  const RegionOracle& oracle;
  const DurixOptions& options;
  DurixReport& report;
  const CancelFn& check_cancelled;
  int next_label = 0;
  /// Removed input vertices attached to a witness cell whose ball covers them within ε (notes
  /// §3.6 and §7.9, witness nodes): when the witness is carved away, they are tested again
  /// against the new path's balls and attached to one of them. So every removed vertex stays
  /// within ε of an output ball.
  std::map<CellId, std::vector<Index>> attached;
  std::vector<CellId> witness;  ///< per vertex: its witness cell (kNoId: not removed)
  /// Per cell: its circumcentre lies strictly inside the input surface (empty: not computed).
  std::vector<char> centre_inside;
  /// Per component: the preferred seed cell (largest ball whose centre is inside the input).
  std::vector<CellId> preferred_seed;

  // Scratch marks (stamped, so no clearing between queries).
  std::vector<std::uint32_t> cell_mark, vertex_mark;
  std::uint32_t stamp = 0;
};

}  // namespace medax::durix
