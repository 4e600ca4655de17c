// The MedialComplex data model (edges from faces, validation, transforms) and Similarity.
#include <medax/medial_complex.hpp>

#include <catch2/catch.hpp>

using namespace medax;

namespace {
MedialComplex two_triangles() {
  MedialComplex m;
  for (int i = 0; i < 4; ++i) m.add_vertex(Vec3(i, i * i, 0), 1.0 + i);
  m.add_face(0, 1, 2);
  m.add_face(2, 1, 3);
  return m;
}
}  // namespace

TEST_CASE("close_edges adds the missing face edges sorted and deduplicated", "[medial]") {
  MedialComplex m = two_triangles();
  m.add_edge(2, 0);  // already a face edge, stored reversed
  m.add_edge(3, 0);  // a free edge
  m.edge_props.fields.add("w", 2, 1.0);
  CHECK(m.close_edges() == 4);
  CHECK(m.edges == std::vector<Segment>{{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}});
  CHECK(m.edge_props.fields.empty());  // rows no longer match: dropped
  CHECK(m.close_edges() == 0);         // idempotent
}

TEST_CASE("close_edges keeps edge properties when nothing changes", "[medial]") {
  MedialComplex m;
  m.add_vertex(Vec3::Zero(), 1);
  m.add_vertex(Vec3::UnitX(), 1);
  m.add_edge(0, 1);
  m.edge_props.labels.add("kind", 1, 7);
  CHECK(m.close_edges() == 0);
  CHECK(m.edge_props.labels.get("kind") == std::vector<int>{7});
}

TEST_CASE("validate names the first inconsistency", "[medial]") {
  MedialComplex m = two_triangles();
  m.add_edge(0, 3);
  CHECK_NOTHROW(m.validate());
  SECTION("face index out of range") {
    m.add_face(0, 1, 9);
    CHECK_THROWS_WITH(m.validate(), "face 2 refers to vertex 9 of 4");
  }
  SECTION("edge index out of range") {
    m.add_edge(4, 0);
    CHECK_THROWS_WITH(m.validate(), "edge 1 refers to vertex 4 of 4");
  }
  SECTION("negative radius") {
    m.radii[2] = -1;
    CHECK_THROWS_WITH(m.validate(), Catch::Contains("vertex 2 has invalid radius"));
  }
  SECTION("non-finite centre") {
    m.centres[1].y() = std::numeric_limits<double>::quiet_NaN();
    CHECK_THROWS_WITH(m.validate(), "vertex 1 has a non-finite centre");
  }
  SECTION("radii and centres of different lengths") {
    m.radii.pop_back();
    CHECK_THROWS_WITH(m.validate(), "4 centres but 3 radii");
  }
  SECTION("property column of the wrong length") {
    m.face_props.fields.add("angle", 3);
    CHECK_THROWS_WITH(m.validate(), "field property 'angle' has 3 values for 2 elements");
  }
  SECTION("generators of the wrong length") {
    m.generators.resize(2);
    CHECK_THROWS_WITH(m.validate(), "2 generator lists for 4 vertices");
  }
}

TEST_CASE("transform maps centres and scales radii", "[medial][geometry]") {
  MedialComplex m = two_triangles();
  m.transform(Similarity{2.0, Vec3(1, -1, 0.5)});
  CHECK(m.centres[3] == Vec3(7, 17, 0.5));
  CHECK(m.radii[3] == 8.0);
  CHECK(m.size(Element::Face) == 2);
}

TEST_CASE("Similarity composition applies the inner map first and inverse undoes it", "[geometry]") {
  const Similarity inner{2.0, Vec3(1, 0, 0)};
  const Similarity outer{0.5, Vec3(0, 3, 0)};
  const Vec3 x(0.25, -4, 10);
  const Similarity both = outer.after(inner);
  CHECK((both.apply(x) - outer.apply(inner.apply(x))).norm() < 1e-15);
  CHECK(both.apply_length(3.0) == 3.0);
  CHECK((both.inverse().apply(both.apply(x)) - x).norm() < 1e-14);
  CHECK((inner.after(inner.inverse()).apply(x) - x).norm() < 1e-14);
  CHECK(inner.inverse().scale == 0.5);
}
