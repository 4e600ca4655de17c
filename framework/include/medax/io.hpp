#pragma once
// Reading and writing meshes, point sets and medial complexes. Every writer is atomic: it writes a
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

/// Point sets: `.xyz` / `.pts` (lines "x y z" or "x y z nx ny nz"; '#' comments; a first line
/// holding only the point count is skipped), and PLY with a vertex element only, OFF (also NOFF,
/// COFF) with 0 faces, OBJ with `v` (and `vn`) lines only. Normals are kept (made unit) when the
/// file gives one per point; otherwise `normals` is empty. Every sample gets an equal share of the
/// estimated surface area (estimate_surface_area). Throws IoError naming the file, the line and
/// what to do.
OrientedSamples read_point_set(const std::filesystem::path& path);
/// Writes `.xyz`: "x y z nx ny nz" per line, or "x y z" when the samples have no normals.
void write_point_set(const std::filesystem::path& path, const OrientedSamples& samples);
/// True for a file read as a point set: `.xyz`/`.pts`, or `.ply`/`.off`/`.obj` with vertices and
/// no faces (judged from the header or the lines; a file it cannot judge is left to read_mesh).
bool is_point_set_file(const std::filesystem::path& path);
/// The shape of an input file: the mesh (read_mesh), or for a point-set file the samples
/// (read_point_set) and no mesh; `source` is the path.
Shape read_shape(const std::filesystem::path& path);
/// Surface area of a sampled surface, estimated from the point density: n times the median over
/// the points of pi r_k^2 / (k - 1), r_k the distance to the k-th nearest other point (the
/// unbiased density estimate of a uniform random sample, k = 8). 0 for fewer than 3 points.
double estimate_surface_area(const std::vector<Vec3>& points);

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
