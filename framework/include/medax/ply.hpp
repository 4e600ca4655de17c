#pragma once
// The one ASCII PLY writer: a file is a list of elements, an element a list of columns. Reals
// are written in the shortest form that reads back exactly; integers as they are.
//
//   PlyElement vertex("vertex", points.size());
//   vertex.real("x", [&](std::size_t i) { return points[i].x(); });
//   write_ply(out, "medax: my points", {vertex});
#include <medax/geometry.hpp>
#include <medax/properties.hpp>

#include <functional>
#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

namespace medax {

class PlyElement {
 public:
  PlyElement(std::string name, std::size_t rows) : name_(std::move(name)), rows_(rows) {}

  /// A `double` column.
  PlyElement& real(std::string name, std::function<double(std::size_t)> value);
  /// An integer column of PLY type `type` ("int", "uchar", ...).
  PlyElement& integer(std::string name, std::function<long long(std::size_t)> value, std::string type = "int");
  /// x, y, z columns of `points`.
  PlyElement& positions(const std::vector<Vec3>& points);
  /// The `vertex_indices` list column of triangles.
  PlyElement& triangles(const std::vector<Tri>& faces);
  /// Every field (double) then every label (int) of `props`, by name (blanks become '_').
  PlyElement& properties(const ElementProperties& props);

  const std::string& name() const { return name_; }
  std::size_t rows() const { return rows_; }
  void write_header(std::ostream& out) const;
  void write_row(std::ostream& out, std::size_t row) const;

 private:
  struct Column {
    std::string header;  // "double x", "list uchar int vertex_indices"
    std::function<void(std::ostream&, std::size_t)> write;
  };
  std::string name_;
  std::size_t rows_;
  std::vector<Column> columns_;
};

/// Writes the header (with `comment`) and every element's rows.
void write_ply(std::ostream& out, std::string_view comment, const std::vector<PlyElement>& elements);

}  // namespace medax
