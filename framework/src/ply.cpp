#include <medax/ply.hpp>

#include <fmt/ostream.h>

#include <cctype>
#include <ostream>

namespace medax {

namespace {
std::string ply_name(std::string name) {
  for (char& c : name)
    if (std::isspace(static_cast<unsigned char>(c))) c = '_';
  return name;
}
}  // namespace

PlyElement& PlyElement::real(std::string name, std::function<double(std::size_t)> value) {
  columns_.push_back({"double " + ply_name(std::move(name)),
                      [value = std::move(value)](std::ostream& out, std::size_t i) { fmt::print(out, "{}", value(i)); }});
  return *this;
}

PlyElement& PlyElement::integer(std::string name, std::function<long long(std::size_t)> value, std::string type) {
  columns_.push_back({type + " " + ply_name(std::move(name)),
                      [value = std::move(value)](std::ostream& out, std::size_t i) { fmt::print(out, "{}", value(i)); }});
  return *this;
}

PlyElement& PlyElement::positions(const std::vector<Vec3>& points) {
  real("x", [&points](std::size_t i) { return points[i].x(); });
  real("y", [&points](std::size_t i) { return points[i].y(); });
  return real("z", [&points](std::size_t i) { return points[i].z(); });
}

PlyElement& PlyElement::triangles(const std::vector<Tri>& faces) {
  columns_.push_back({"list uchar int vertex_indices", [&faces](std::ostream& out, std::size_t i) {
                        fmt::print(out, "3 {} {} {}", faces[i][0], faces[i][1], faces[i][2]);
                      }});
  return *this;
}

PlyElement& PlyElement::properties(const ElementProperties& props) {
  for (const auto& [name, column] : props.fields.all()) real(name, [&column = column](std::size_t i) { return column[i]; });
  for (const auto& [name, column] : props.labels.all())
    integer(name, [&column = column](std::size_t i) { return column[i]; });
  return *this;
}

void PlyElement::write_header(std::ostream& out) const {
  fmt::print(out, "element {} {}\n", name_, rows_);
  for (const Column& c : columns_) fmt::print(out, "property {}\n", c.header);
}

void PlyElement::write_row(std::ostream& out, std::size_t row) const {
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    if (c) out << ' ';
    columns_[c].write(out, row);
  }
  out << '\n';
}

void write_ply(std::ostream& out, std::string_view comment, const std::vector<PlyElement>& elements) {
  out << "ply\nformat ascii 1.0\n";
  if (!comment.empty()) fmt::print(out, "comment {}\n", comment);
  for (const PlyElement& e : elements) e.write_header(out);
  out << "end_header\n";
  for (const PlyElement& e : elements)
    for (std::size_t i = 0; i < e.rows(); ++i) e.write_row(out, i);
}

}  // namespace medax
