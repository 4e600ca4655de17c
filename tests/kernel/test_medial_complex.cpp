// The MedialComplex data model (edges from faces, validation, transforms) and Similarity.
#include <medax/medial_complex.hpp>

#include <catch2/catch.hpp>

#include <utility>

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
  auto& w = m.edge_props.fields.add("w", 2, -1.0);  // added edges get -1
  w = {20, 30};                                     // rows of (2, 0) and (3, 0)
  CHECK(m.close_edges() == 4);
  CHECK(m.edges == std::vector<Segment>{{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}});
  // Surviving edges keep their rows; added ones take the column's initial value.
  CHECK(m.edge_props.fields.get("w") == std::vector<double>{-1, 20, 30, -1, -1, -1});
  CHECK(m.close_edges() == 0);  // idempotent
  CHECK_NOTHROW(m.validate());
}

TEST_CASE("close_edges keeps the first row of an edge given twice", "[medial]") {
  MedialComplex m = two_triangles();
  m.add_edge(1, 0);
  m.add_edge(0, 1);
  m.edge_props.labels.add("k", 2) = {5, 6};
  m.close_edges();
  CHECK(m.edges.front() == Segment{0, 1});
  CHECK(m.edge_props.labels.get("k").front() == 5);
}

TEST_CASE("adding elements grows every column of their kind with its initial value", "[medial]") {
  const Property<double> et{Element::Vertex, "et"};
  const Property<int> sheet{Element::Face, "sheet"};
  const Property<double> weight{Element::Edge, "weight"};
  MedialComplex m = two_triangles();
  m.add(et, 0.5);
  m.add(sheet, -1);
  m.add(weight, 2.0);
  m.generator_kind = "mesh_vertex";
  m.generators.resize(m.num_vertices());
  const Index v = m.add_vertex(Vec3(5, 5, 5), 1);
  m.add_face(0, 1, v);
  m.add_edge(0, v);
  CHECK(m.get(et).size() == 5);
  CHECK(m.get(et)[v] == 0.5);
  CHECK(m.get(sheet) == std::vector<int>{-1, -1, -1});
  CHECK(m.get(weight) == std::vector<double>{2.0});
  CHECK(m.generators.size() == 5);
  CHECK(m.has(et));
  CHECK_FALSE(m.has(Property<double>{Element::Face, "et"}));  // same name, other element
  CHECK_THROWS_AS(m.get(Property<int>{Element::Vertex, "et"}), std::out_of_range);  // a field, not a label
  CHECK_NOTHROW(m.validate());
}

TEST_CASE("subcomplex keeps the chosen elements with their columns and generators", "[medial]") {
  MedialComplex m = two_triangles();  // faces (0 1 2), (2 1 3)
  m.close_edges();
  m.add(Property<double>{Element::Vertex, "r2"}) = {0, 1, 4, 9};
  m.add(Property<int>{Element::Face, "id"}) = {10, 11};
  auto& length = m.add(Property<double>{Element::Edge, "len"});
  for (std::size_t e = 0; e < m.edges.size(); ++e) length[e] = 10.0 * m.edges[e][0] + m.edges[e][1];
  m.generator_kind = "sample";
  m.generators = {{0}, {1}, {2}, {3}};

  // The second triangle and its three edges: vertices 1, 2, 3 become 0, 1, 2.
  std::vector<Index> edges;
  for (Index e = 0; e < m.edges.size(); ++e)
    if (m.edges[e][0] != 0) edges.push_back(e);
  const MedialComplex sub = m.subcomplex({1, 2, 3}, edges, {1});
  CHECK(sub.faces == std::vector<Tri>{{1, 0, 2}});
  CHECK(sub.edges == std::vector<Segment>{{0, 1}, {0, 2}, {1, 2}});
  CHECK(sub.vertex_props.fields.get("r2") == std::vector<double>{1, 4, 9});
  CHECK(sub.face_props.labels.get("id") == std::vector<int>{11});
  CHECK(sub.edge_props.fields.get("len") == std::vector<double>{12, 13, 23});  // old (1,2), (1,3), (2,3)
  CHECK(sub.generators == std::vector<std::vector<Index>>{{1}, {2}, {3}});
  CHECK(sub.generator_kind == "sample");
  CHECK_NOTHROW(sub.validate());
  CHECK_THROWS_WITH(m.subcomplex({1, 2}, {}, {1}), Catch::Contains("vertex 3 is used but not kept"));
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

TEST_CASE("transform scales each field by the scale to its length power, and keeps labels", "[medial][geometry]") {
  const Property<double> distance{Element::Vertex, "burn", 1}, area{Element::Face, "area", 2},
      angle{Element::Vertex, "angle"};
  const Property<int> label{Element::Vertex, "sheet"};
  MedialComplex m = two_triangles();
  m.add(distance, 1.5);
  m.add(area, 3.0);
  m.add(angle, 0.25);
  m.add(label, 7);
  const MedialComplex kept = m.subcomplex({0, 1, 2}, {}, {0});  // a selection keeps the powers
  for (const MedialComplex* c : {&std::as_const(m), &kept}) {
    MedialComplex t = *c;
    t.transform(Similarity{2.0, Vec3(1, -1, 0.5)});
    CHECK(t.get(distance)[0] == 3.0);
    CHECK(t.get(area)[0] == 12.0);
    CHECK(t.get(angle)[0] == 0.25);
    CHECK(t.get(label)[0] == 7);
  }
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
