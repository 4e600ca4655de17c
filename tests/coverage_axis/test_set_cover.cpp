// The set-cover solvers on abstract instances: the exact solve against brute force, with and
// without presolve; the greedy covers and the local search against it; the proven-optimal flag
// against known optima.
#include "presolve.hpp"
#include "set_cover_exact.hpp"
#include "set_cover_greedy.hpp"
#include "set_cover_local_search.hpp"

#include <catch2/catch.hpp>
#include <tbb/global_control.h>

#include <random>

using namespace medax;
using namespace medax::coverage_axis;

namespace {

/// A random coverable instance: each column covers each row with probability `density`, and a
/// row no column covers gets one random column.
SetCover random_instance(std::size_t rows, std::size_t columns, double density, std::mt19937_64& rng) {
  std::bernoulli_distribution hit(density);
  std::uniform_int_distribution<Index> any_column(0, static_cast<Index>(columns - 1));
  SetCover c;
  c.rows = rows;
  c.columns.resize(columns);
  for (Index r = 0; r < rows; ++r) {
    bool covered = false;
    for (auto& column : c.columns)
      if (hit(rng)) column.push_back(r), covered = true;
    if (!covered) c.columns[any_column(rng)].push_back(r);
  }
  for (auto& column : c.columns) std::sort(column.begin(), column.end());
  return c;
}

/// The minimum cover size by enumerating every subset of columns.
std::size_t brute_force_minimum(const SetCover& c) {
  const std::size_t n = c.columns.size();
  std::size_t best = n + 1;
  for (std::uint32_t mask = 0; mask < (1u << n); ++mask) {
    const std::size_t size = static_cast<std::size_t>(__builtin_popcount(mask));
    if (size >= best) continue;
    std::vector<Index> chosen;
    for (Index j = 0; j < n; ++j)
      if (mask & (1u << j)) chosen.push_back(j);
    if (covers_all(c, chosen)) best = size;
  }
  return best;
}

/// Vertex cover of the complete graph K_n as a set cover: rows = edges, columns = vertices.
/// Optimum n − 1, LP relaxation n / 2 (every x = 1/2): an integrality gap.
SetCover complete_graph_vertex_cover(Index n) {
  SetCover c;
  c.columns.resize(n);
  for (Index a = 0; a < n; ++a)
    for (Index b = a + 1; b < n; ++b) {
      c.columns[a].push_back(static_cast<Index>(c.rows));
      c.columns[b].push_back(static_cast<Index>(c.rows));
      ++c.rows;
    }
  return c;
}

/// The classic trap for the greedy: two halves of 2^k − 1 rows each, split into blocks of 1, 2,
/// 4, … rows; one column per half (the optimum, 2), and one column per block size covering that
/// block in both halves, which the greedy takes first, largest first (k columns).
SetCover greedy_trap(Index k) {
  const Index half = (1u << k) - 1;
  SetCover c;
  c.rows = 2 * half;
  c.columns.resize(2 + k);
  for (Index r = 0; r < half; ++r) c.columns[0].push_back(r), c.columns[1].push_back(half + r);
  for (Index b = 0, first = 0; b < k; first += 1u << b, ++b)
    for (Index r = first; r < first + (1u << b); ++r) c.columns[2 + b].push_back(r), c.columns[2 + b].push_back(half + r);
  for (auto& column : c.columns) std::sort(column.begin(), column.end());
  return c;
}

}  // namespace

TEST_CASE("exact cover: equals brute force on 40 small random instances, with and without presolve",
          "[coverage_axis][exact]") {
  std::mt19937_64 rng(7);
  for (int instance = 0; instance < 40; ++instance) {
    const std::size_t columns = 6 + instance % 9;  // 6..14
    const SetCover c = random_instance(10 + instance % 11, columns, 0.25, rng);
    const std::size_t optimum = brute_force_minimum(c);
    const ExactResult with = solve_exact(c, ExactOptions{});
    ExactOptions plain;
    plain.presolve = false;
    const ExactResult without = solve_exact(c, plain);
    INFO("instance " << instance);
    CHECK(covers_all(c, with.chosen));
    CHECK(covers_all(c, without.chosen));
    CHECK(with.chosen.size() == optimum);
    CHECK(without.chosen.size() == optimum);
    CHECK(with.proven_optimal);
    CHECK(with.lp_bound <= optimum + 1e-6);
    // Greedy covers are covers, and never smaller than the minimum.
    CHECK(textbook_greedy(c).size() >= optimum);
  }
}

TEST_CASE("presolve: forced picks plus the reduced optimum give the optimum", "[coverage_axis][presolve]") {
  std::mt19937_64 rng(11);
  for (int instance = 0; instance < 20; ++instance) {
    const SetCover c = random_instance(14, 12, 0.2, rng);
    const Presolved p = presolve(c);
    INFO("instance " << instance);
    for (const auto& column : p.reduced.columns)
      for (Index r : column) CHECK(r < p.reduced.rows);
    CHECK(p.column_of.size() == p.reduced.columns.size());
    const std::size_t reduced = p.reduced.rows == 0 ? 0 : brute_force_minimum(p.reduced);
    CHECK(p.forced.size() + reduced == brute_force_minimum(c));
  }
  SECTION("a row with one column forces it; a duplicate column and an implied row go") {
    SetCover c;
    c.rows = 4;
    c.columns = {{0, 1}, {1, 2, 3}, {1, 2, 3}, {2}};
    const Presolved p = presolve(c);
    CHECK(p.forced == std::vector<Index>{0, 1});
    CHECK(p.reduced.rows == 0);
    CHECK(p.stats.dominated_columns >= 1);
  }
}

TEST_CASE("exact cover: the proven flag is honest where the LP bound is not tight", "[coverage_axis][exact]") {
  for (Index n : {5u, 6u, 7u}) {
    const SetCover c = complete_graph_vertex_cover(n);
    const ExactResult r = solve_exact(c, ExactOptions{});
    INFO("K_" << n);
    CHECK(r.chosen.size() == n - 1);
    CHECK(r.lp_bound == Approx(n / 2.0));
    CHECK(std::ceil(r.lp_bound - 1e-6) < r.chosen.size());  // the LP alone certifies nothing
    CHECK(r.proven_optimal);                                // CBC's search does
    CHECK(r.gap == 0);
  }
  SECTION("stopped before branching: proven only with a bound that matches, else a positive gap") {
    const SetCover c = complete_graph_vertex_cover(9);
    const ExactResult r = solve_exact(c, ExactOptions{}, [](double, double, double) { return false; });
    CHECK(covers_all(c, r.chosen));
    if (r.proven_optimal) {
      CHECK(r.chosen.size() == 8);
      CHECK(std::ceil(r.lower_bound - 1e-6) == 8);
    } else {
      CHECK(r.gap > 0);
      CHECK(r.gap == Approx((r.chosen.size() - std::ceil(r.lower_bound - 1e-6)) / r.chosen.size()));
    }
  }
}

TEST_CASE("CA++: with λ_u = λ_c = 0 it is the textbook greedy; it never beats the exact cover",
          "[coverage_axis][greedy]") {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int instance = 0; instance < 20; ++instance) {
    const SetCover c = random_instance(60, 40, 0.08, rng);
    Balls balls;
    for (std::size_t j = 0; j < c.columns.size(); ++j)
      balls.centres.push_back({unit(rng), unit(rng), unit(rng)}), balls.radii.push_back(0.05 + unit(rng));
    GreedyOptions plain;
    plain.lambda_uniformity = plain.lambda_centrality = 0;
    INFO("instance " << instance);
    CHECK(ca_plus_plus(c, balls, plain) == textbook_greedy(c));
    const std::size_t optimum = solve_exact(c, ExactOptions{}).chosen.size();
    for (Penalty penalty : {Penalty::Ratio, Penalty::Standardized}) {
      GreedyOptions paper;
      paper.penalty = penalty;
      const std::vector<Index> chosen = ca_plus_plus(c, balls, paper);
      CHECK(covers_all(c, chosen));
      CHECK(chosen.size() >= optimum);
    }
    GreedyOptions capped;
    capped.target = 3;
    CHECK(ca_plus_plus(c, balls, capped).size() == 3);
  }
}

TEST_CASE("local search: a cover between the optimum and the greedy, reproducible", "[coverage_axis][local_search]") {
  std::mt19937_64 rng(5);
  for (int instance = 0; instance < 40; ++instance) {
    const SetCover c = random_instance(12 + instance % 9, 6 + instance % 9, 0.25, rng);
    const std::vector<Index> greedy = textbook_greedy(c);
    LocalSearchOptions options;
    options.iterations = 2000;
    const std::vector<Index> found = local_search_cover(c, greedy, options);
    INFO("instance " << instance);
    CHECK(covers_all(c, found));
    CHECK(std::is_sorted(found.begin(), found.end()));
    CHECK(found.size() >= brute_force_minimum(c));
    CHECK(found.size() <= greedy.size());
    CHECK(local_search_cover(c, greedy, options) == found);
  }
  SECTION("the same cover on 1 and 4 threads (the runs are combined in run order)") {
    const SetCover c = random_instance(120, 90, 0.06, rng);
    LocalSearchOptions options;
    options.iterations = 3000;
    std::vector<Index> by_threads[2];
    for (int t = 0; t < 2; ++t) {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, t == 0 ? 1 : 4);
      by_threads[t] = local_search_cover(c, textbook_greedy(c), options);
    }
    CHECK(by_threads[0] == by_threads[1]);
  }
  SECTION("it leaves the greedy's trap: k block columns become the two half columns") {
    const SetCover c = greedy_trap(5);
    const std::vector<Index> greedy = textbook_greedy(c);
    CHECK(greedy.size() == 5);
    CHECK(local_search_cover(c, greedy, LocalSearchOptions{}) == std::vector<Index>{0, 1});
  }
  SECTION("no steps: the start without redundant columns (each covers a row no other one does)") {
    const SetCover c = greedy_trap(3);
    LocalSearchOptions none;
    none.iterations = 0;
    const std::vector<Index> kept = local_search_cover(c, {0, 1, 2, 3, 4}, none);
    CHECK(covers_all(c, kept));
    CHECK(kept.size() < 5);
    for (Index j : kept) {
      std::vector<Index> without;
      std::copy_if(kept.begin(), kept.end(), std::back_inserter(without), [&](Index k) { return k != j; });
      CHECK_FALSE(covers_all(c, without));
    }
  }
  SECTION("the exact solve reports greedy, warm start and solution sizes in that order") {
    const SetCover c = greedy_trap(4);
    ExactOptions plain;  // the presolve would merge each block's rows and leave the greedy no trap
    plain.presolve = false;
    const ExactResult r = solve_exact(c, plain);
    CHECK(r.greedy == 4);
    CHECK(r.warm_start == 2);
    CHECK(r.chosen == std::vector<Index>{0, 1});
    CHECK(r.proven_optimal);
  }
}
