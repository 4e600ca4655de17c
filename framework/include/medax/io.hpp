#pragma once
// Reading and writing meshes and medial complexes. Every writer is atomic: it writes a
// temporary file beside the target and renames it, so no half-written file is ever left.
#include <medax/medial_complex.hpp>
#include <medax/surface.hpp>

#include <filesystem>
#include <functional>
#include <iosfwd>
#include <stdexcept>

namespace medax {

/// An I/O failure, with the file (and line, where known) in its message.
struct IoError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Reads OFF, OBJ, PLY or STL (by extension). Polygons are fan-triangulated. Throws IoError.
SurfaceMesh read_mesh(const std::filesystem::path& path);
/// Writes OFF, OBJ, PLY or STL (by extension).
void write_mesh(const std::filesystem::path& path, const SurfaceMesh& mesh);

/// `.ma`: "nv ne nf", then "v x y z r", "e i j", "f i j k", 0-based (Q-MAT, Coverage Axis,
/// MATFP, MATTopo). Reading accepts blank lines and '#' comments; errors name file:line.
MedialComplex read_ma(const std::filesystem::path& path);
void write_ma(const std::filesystem::path& path, const MedialComplex& medial);
/// ASCII PLY: vertex x y z radius + every vertex field/label, edge and face elements with
/// their fields/labels as properties (MeshLab reads it).
void write_medial_ply(const std::filesystem::path& path, const MedialComplex& medial);
/// OBJ: "v" lines, "l" for edges, "f" for triangles (1-based); radii are not representable.
void write_medial_obj(const std::filesystem::path& path, const MedialComplex& medial);
/// Reads `.ma` or writes by extension (.ma, .ply, .obj).
MedialComplex read_medial(const std::filesystem::path& path);
void write_medial(const std::filesystem::path& path, const MedialComplex& medial);

/// Writes `path` atomically: `body` writes into a temporary file in the same folder, which is
/// renamed over `path` only when `body` returns and the file is flushed and fsynced without
/// error (the folder is fsynced after the rename where the file system allows). On any failure
/// the temporary file is removed and `path` is left as it was.
void write_file_atomic(const std::filesystem::path& path,
                       const std::function<void(std::ostream&)>& body);

}  // namespace medax
