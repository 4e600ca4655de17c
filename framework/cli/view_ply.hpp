#pragma once
// Reading back the ASCII PLY files medax writes (medial.ply and the extra files of stages, e.g.
// durix_segmentation.ply): every element with its scalar properties by name, and its one list
// property (a face's vertex_indices) fan-triangulated.
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace medax::cli {

struct PlyProperty {
  std::string name;
  bool integer = false;        ///< int/uchar/... (a label), else float/double (a field)
  std::vector<double> values;  ///< one per row
};

struct PlyTable {
  std::string name;
  std::size_t rows = 0;
  std::vector<PlyProperty> properties;    ///< the scalar properties, in file order
  std::vector<std::uint32_t> triangles;   ///< the list property fanned into triangles, 3 per
  std::vector<std::size_t> triangle_row;  ///< the row each triangle came from

  const PlyProperty* find(const std::string& property) const;
};

/// The elements of an ASCII PLY file by name. Throws std::runtime_error naming the file and
/// line when it is binary, truncated or not a number where one is expected.
std::map<std::string, PlyTable> read_ply_tables(const std::filesystem::path& path);

}  // namespace medax::cli
