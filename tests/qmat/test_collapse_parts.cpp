// The collapse loop's parts that exist for speed must not change what it computes: the queue
// pops live entries in (cost, lo, hi) order whatever its sweeps do, the gathered fans of the
// flip test answer as testing each face around the edge directly does, and the pooled lists
// hold what separate vectors would.
#include "collapse_queue.hpp"
#include "flip_test.hpp"
#include "list_pool.hpp"
#include "qmat_test_inputs.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <random>
#include <set>
#include <tuple>

using namespace medax;
using namespace medax::qmat;

TEST_CASE("the collapse queue pops its live entries in (cost, lo, hi) order across sweeps", "[qmat][collapse]") {
  // Entries of edge (lo, hi) are live while neither end changed after they were pushed: a
  // change stamps the vertex with its number.
  std::vector<std::uint32_t> stamp(50, 0);
  std::uint32_t changes = 0;
  CollapseQueue queue(stamp);
  std::multiset<std::tuple<double, Index, Index>> live;  // the reference
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<Index> vertex(0, 48);
  std::uniform_int_distribution<int> cost(0, 40);  // few distinct costs: many ties
  auto push = [&](bool ordered) {
    const Index lo = vertex(rng), hi = lo + 1;
    const QueuedCollapse c{double(cost(rng)), lo, hi, changes, Vec4(lo, hi, 0, 1)};
    ordered ? queue.push(c) : queue.push_unordered(c);
    live.insert({c.cost, lo, hi});
  };
  for (int k = 0; k < 3000; ++k) push(false);
  queue.heapify();
  std::size_t popped = 0;
  while (!queue.empty()) {
    const QueuedCollapse c = queue.pop();
    if (stamp[c.lo] > c.seq || stamp[c.hi] > c.seq) continue;
    REQUIRE(!live.empty());
    const auto& [cost_, lo, hi] = *live.begin();
    CHECK(std::tie(c.cost, c.lo, c.hi) == std::tie(cost_, lo, hi));
    CHECK(c.sphere == Vec4(lo, hi, 0, 1));
    live.erase(live.begin());
    ++popped;
    // As the collapse does: a change of lo makes the entries holding it stale, then new ones are pushed.
    if (popped % 3 == 0) {
      stamp[c.lo] = ++changes;
      for (auto it = live.begin(); it != live.end();)
        it = std::get<1>(*it) == c.lo || std::get<2>(*it) == c.lo ? live.erase(it) : std::next(it);
      for (int k = 0; k < 12 && popped < 20000; ++k) push(true);
    }
  }
  CHECK(live.empty());
  CHECK(popped > 3000);
}

TEST_CASE("the flip test's fans answer as testing each face around the edge directly", "[qmat][collapse]") {
  const MedialComplex axis = test::voronoi_axis("joint.off");
  const CollapseMesh mesh(axis, 1.0);
  FlipTest fans(mesh);
  // The reference: every live face around i or j that does not hold both, not a sliver, whose
  // normal turns by more than 90° when its moving corner goes to `centre`.
  auto direct = [&](Index i, Index j, const Vec3& centre) {
    for (Index end : {i, j}) {
      if (centre_of(mesh.spheres[end]) == centre) continue;
      const Index other = end == i ? j : i;
      bool flipped = false;
      mesh.for_each_face(end, [&](Index f) {
        Tri t = mesh.face(f);
        if (t[0] == other || t[1] == other || t[2] == other) return;
        while (t[0] != end) std::rotate(t.begin(), t.begin() + 1, t.end());
        const Vec3 p = centre_of(mesh.spheres[end]), a = centre_of(mesh.spheres[t[1]]), b = centre_of(mesh.spheres[t[2]]);
        const Vec3 n0 = (a - p).cross(b - p);
        if (!(n0.squaredNorm() > 1e-6 * 1e-6 * (a - p).squaredNorm() * (b - p).squaredNorm())) return;
        flipped = flipped || n0.dot((a - centre).cross(b - centre)) < 0;
      });
      if (flipped) return true;
    }
    return false;
  };
  std::mt19937_64 rng(5);
  std::normal_distribution<double> jitter(0, 0.02);
  std::size_t flips = 0, tested = 0;
  for (Index i = 0; i < mesh.size(); ++i)
    for (Index j : mesh.neighbours(i)) {
      if (j < i || !mesh.has_faces(i)) continue;
      const Vec4 mean = 0.5 * (mesh.spheres[i] + mesh.spheres[j]);
      for (const Vec3& centre : {centre_of(mesh.spheres[i]), centre_of(mean),
                                 Vec3(centre_of(mean) + Vec3(jitter(rng), jitter(rng), jitter(rng)))}) {
        const bool expected = direct(i, j, centre);
        CHECK(fans.flips(i, j, centre) == expected);
        flips += expected;
        ++tested;
      }
    }
  CHECK(tested > 1000);
  CHECK(flips > 10);            // both answers occur
  CHECK(flips < tested - 10);
}

TEST_CASE("pooled lists hold what separate sorted vectors hold, through growth and moves", "[qmat][collapse]") {
  const std::vector<std::size_t> room = {0, 1, 3, 2, 5, 0, 4, 1};
  ListPool pool(room);
  std::vector<std::vector<Index>> reference(room.size());
  std::mt19937_64 rng(9);
  std::uniform_int_distribution<std::size_t> list(0, room.size() - 1);
  std::uniform_int_distribution<Index> value(0, 30);
  std::uniform_int_distribution<int> action(0, 9);
  for (int step = 0; step < 20000; ++step) {
    const std::size_t v = list(rng);
    const Index x = value(rng);
    std::vector<Index>& ref = reference[v];
    const auto at = std::lower_bound(ref.begin(), ref.end(), x);
    const int a = action(rng);
    if (a < 5) {
      pool.insert_sorted(v, x);
      if (at == ref.end() || *at != x) ref.insert(at, x);
    } else if (a < 9) {
      pool.erase_sorted(v, x);
      if (at != ref.end() && *at == x) ref.erase(at);
    } else {
      pool.erase_if(v, [&](Index y) { return y % 3 == x % 3; });
      ref.erase(std::remove_if(ref.begin(), ref.end(), [&](Index y) { return y % 3 == x % 3; }), ref.end());
    }
    for (std::size_t w = 0; w < room.size(); ++w) {
      const ListPool::View got = pool[w];
      REQUIRE(std::vector<Index>(got.begin(), got.end()) == reference[w]);
    }
  }
  pool.clear(5);
  CHECK(pool[5].size() == 0);
  for (Index x : {7u, 3u, 7u, 1u, 3u}) pool.push_back(5, x);
  pool.sort_unique(5);
  CHECK(std::vector<Index>(pool[5].begin(), pool[5].end()) == std::vector<Index>{1, 3, 7});
}
