// Medial complex I/O: the `.ma` text format, PLY with properties, OBJ.
#include <medax/io.hpp>
#include <medax/ply.hpp>

#include <fmt/format.h>
#include <fmt/ostream.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>

namespace medax {

namespace fs = std::filesystem;

namespace {

std::string lower_extension(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

/// Reads whitespace-separated tokens line by line, remembering the line for error messages.
class LineReader {
 public:
  explicit LineReader(const fs::path& path) : path_(path), in_(path) {
    if (!in_) throw IoError(fmt::format("{}: cannot open file", path.string()));
  }
  /// Next non-blank, non-comment line split into tokens; false at end of file.
  bool next(std::vector<std::string>& tokens) {
    std::string line;
    while (std::getline(in_, line)) {
      ++line_number_;
      const auto hash = line.find('#');
      if (hash != std::string::npos) line.erase(hash);
      std::istringstream words(line);
      tokens.clear();
      for (std::string w; words >> w;) tokens.push_back(w);
      if (!tokens.empty()) return true;
    }
    return false;
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw IoError(fmt::format("{}:{}: {}", path_.string(), line_number_, what));
  }
  double number(const std::string& token) const {
    try {
      std::size_t used = 0;
      const double v = std::stod(token, &used);
      if (used == token.size() && std::isfinite(v)) return v;
      if (used == token.size()) fail(fmt::format("'{}' is not a finite number (fix or remove the element)", token));
    } catch (const std::logic_error&) {  // stod: invalid_argument, out_of_range
    }
    fail(fmt::format("'{}' is not a number", token));
  }
  Index index(const std::string& token, std::size_t count) const {
    const double v = number(token);
    if (v < 0 || v >= static_cast<double>(count) || v != std::floor(v))
      fail(fmt::format("vertex index {} is not in 0..{}", token, count == 0 ? 0 : count - 1));
    return static_cast<Index>(v);
  }

 private:
  fs::path path_;
  std::ifstream in_;
  std::size_t line_number_ = 0;
};

}  // namespace

MedialComplex read_ma(const fs::path& path) {
  LineReader reader(path);
  std::vector<std::string> t;
  if (!reader.next(t)) throw IoError(fmt::format("{}: empty file; a .ma file starts with 'nv ne nf'", path.string()));
  if (t.size() != 3) reader.fail("the first line must be 'nv ne nf' (three counts)");
  const auto count = [&](const std::string& s) {
    const double v = reader.number(s);
    if (v < 0 || v > 1e18 || v != std::floor(v)) reader.fail("counts must be whole numbers >= 0");
    return static_cast<std::size_t>(v);
  };
  const std::size_t nv = count(t[0]), ne = count(t[1]), nf = count(t[2]);
  // Checked before anything is reserved: "v 0 0 0 0\n" takes 10 bytes, "e 0 1\n" 6, "f 0 1 2\n" 8.
  const auto bytes = fs::file_size(path);
  const long double needed = 10.0L * nv + 6.0L * ne + 8.0L * nf - 1;
  if (needed > static_cast<long double>(bytes))
    reader.fail(fmt::format("the header announces {} vertices, {} edges and {} faces but the file has only {} bytes "
                            "(at least {:.0f} needed): the file is truncated or its header is wrong",
                            nv, ne, nf, bytes, static_cast<double>(needed)));
  MedialComplex mc;
  mc.centres.reserve(nv);
  mc.radii.reserve(nv);
  while (reader.next(t)) {
    const std::string& tag = t[0];
    if (tag == "v") {
      // Extra trailing numbers (the deleted/feature flag of some writers) are checked and ignored.
      if (t.size() < 5) reader.fail("a vertex line is 'v x y z r'");
      for (std::size_t k = 5; k < t.size(); ++k) reader.number(t[k]);
      if (!mc.edges.empty() || !mc.faces.empty()) reader.fail("vertices must come before edges and faces");
      const double r = reader.number(t[4]);
      if (!(r >= 0)) reader.fail("the radius must be >= 0");
      mc.add_vertex(Vec3(reader.number(t[1]), reader.number(t[2]), reader.number(t[3])), r);
    } else if (tag == "e") {
      if (t.size() < 3) reader.fail("an edge line is 'e i j'");
      for (std::size_t k = 3; k < t.size(); ++k) reader.number(t[k]);
      mc.add_edge(reader.index(t[1], nv), reader.index(t[2], nv));
    } else if (tag == "f") {
      if (t.size() < 4) reader.fail("a face line is 'f i j k'");
      for (std::size_t k = 4; k < t.size(); ++k) reader.number(t[k]);
      mc.add_face(reader.index(t[1], nv), reader.index(t[2], nv), reader.index(t[3], nv));
    } else {
      reader.fail(fmt::format("unknown line type '{}' (expected v, e or f)", tag));
    }
    if (mc.centres.size() > nv) reader.fail(fmt::format("more vertices than the {} the header announces", nv));
  }
  if (mc.centres.size() != nv || mc.edges.size() != ne || mc.faces.size() != nf)
    throw IoError(fmt::format("{}: the header announces {} {} {} (v e f) but the file has {} {} {}",
                              path.string(), nv, ne, nf, mc.centres.size(), mc.edges.size(),
                              mc.faces.size()));
  return mc;
}

void write_ma(const fs::path& path, const MedialComplex& mc) {
  write_file_atomic(path, [&](std::ostream& out) {
    fmt::print(out, "{} {} {}\n", mc.centres.size(), mc.edges.size(), mc.faces.size());
    for (std::size_t i = 0; i < mc.centres.size(); ++i)
      fmt::print(out, "v {} {} {} {}\n", mc.centres[i].x(), mc.centres[i].y(), mc.centres[i].z(), mc.radii[i]);
    for (const Segment& e : mc.edges) fmt::print(out, "e {} {}\n", e[0], e[1]);
    for (const Tri& f : mc.faces) fmt::print(out, "f {} {} {}\n", f[0], f[1], f[2]);
  });
}

void write_medial_ply(const fs::path& path, const MedialComplex& mc) {
  PlyElement vertex("vertex", mc.centres.size());
  vertex.positions(mc.centres).real("radius", [&mc](std::size_t i) { return mc.radii[i]; }).properties(mc.vertex_props);
  PlyElement edge("edge", mc.edges.size());
  edge.integer("vertex1", [&mc](std::size_t i) { return mc.edges[i][0]; })
      .integer("vertex2", [&mc](std::size_t i) { return mc.edges[i][1]; })
      .properties(mc.edge_props);
  PlyElement face("face", mc.faces.size());
  face.triangles(mc.faces).properties(mc.face_props);
  write_file_atomic(path, [&](std::ostream& out) { write_ply(out, "medax medial complex", {vertex, edge, face}); });
}

void write_medial_obj(const fs::path& path, const MedialComplex& mc) {
  write_file_atomic(path, [&](std::ostream& out) {
    out << "# medax medial complex (radii are in the .ma and .ply outputs)\n";
    for (const Vec3& c : mc.centres) fmt::print(out, "v {} {} {}\n", c.x(), c.y(), c.z());
    for (const Segment& e : mc.edges) fmt::print(out, "l {} {}\n", e[0] + 1, e[1] + 1);
    for (const Tri& f : mc.faces) fmt::print(out, "f {} {} {}\n", f[0] + 1, f[1] + 1, f[2] + 1);
  });
}

MedialComplex read_medial(const fs::path& path) {
  if (lower_extension(path) != ".ma")
    throw IoError(fmt::format("{}: medial complexes are read from .ma files", path.string()));
  return read_ma(path);
}

void write_medial(const fs::path& path, const MedialComplex& mc) {
  const std::string ext = lower_extension(path);
  if (ext == ".ma") write_ma(path, mc);
  else if (ext == ".ply") write_medial_ply(path, mc);
  else if (ext == ".obj") write_medial_obj(path, mc);
  else throw IoError(fmt::format("{}: unsupported medial format '{}' (use .ma, .ply or .obj)", path.string(), ext));
}

}  // namespace medax
