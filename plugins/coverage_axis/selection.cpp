#include "selection.hpp"

#include <nlohmann/json.hpp>

#include <limits>
#include <ostream>

namespace medax::coverage_axis {

void write_selection_json(std::ostream& out, const Selection& s) {
  nlohmann::ordered_json spheres = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < s.centres.size(); ++i)
    spheres.push_back({s.centres[i].x(), s.centres[i].y(), s.centres[i].z(), s.radii[i]});
  nlohmann::ordered_json j;
  j["mode"] = s.mode;
  j["candidates"] = s.candidates;
  j["samples"] = s.samples;
  j["uncovered"] = s.uncovered;
  j["candidate_count"] = s.candidate_count;
  j["undominated"] = s.undominated;
  j["dilation"] = s.dilation;
  j["objective"] = s.objective;
  j["lp_bound"] = s.lp_bound;
  j["lower_bound"] = s.lower_bound;
  j["proven_optimal"] = s.proven_optimal;
  j["gap"] = s.gap;
  j["greedy"] = s.greedy;
  j["warm_start"] = s.warm_start;
  j["nodes"] = s.nodes;
  j["presolve"] = {{"forced", s.forced}, {"dominated_columns", s.dominated_columns},
                   {"dominated_rows", s.dominated_rows}, {"rows", s.rows}, {"columns", s.columns},
                   {"nonzeros", s.nonzeros}};
  j["seconds"] = {{"candidates", s.seconds_candidates}, {"matrix", s.seconds_matrix},
                  {"presolve", s.seconds_presolve}, {"lp", s.seconds_lp}, {"search", s.seconds_search},
                  {"solve", s.seconds_solve}};
  j["marked"] = s.marked;
  j["spheres"] = std::move(spheres);
  out << j.dump(1) << '\n';
}

std::size_t mark_nearest_vertices(MedialComplex& medial, const std::vector<Vec3>& centres) {
  if (!medial.has(kSelected)) medial.add(kSelected, 0);
  std::vector<int>& selected = medial.get(kSelected);
  std::fill(selected.begin(), selected.end(), 0);
  std::size_t marked = 0;
  for (const Vec3& c : centres) {
    Index best = 0;
    double best_distance = std::numeric_limits<double>::infinity();
    for (Index v = 0; v < medial.num_vertices(); ++v) {
      const double d = (medial.centres[v] - c).squaredNorm();
      if (!selected[v] && d < best_distance) best = v, best_distance = d;
    }
    if (best_distance == std::numeric_limits<double>::infinity()) break;  // every vertex is marked
    selected[best] = 1;
    ++marked;
  }
  return marked;
}

}  // namespace medax::coverage_axis
