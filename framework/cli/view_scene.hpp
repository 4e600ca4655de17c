#pragma once
// What the viewer shows of a run folder, read back from its files: the medial complex with every
// field it carries, the input surface, the reconstruction and other surfaces the stages wrote.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace medax::cli {

/// A per-element column of the medial complex: a field (real) or a label (integer).
struct ViewField {
  std::string name;
  std::string element;  ///< "vertex", "edge" (on curves) or "face" (on triangles)
  bool label = false;
  std::vector<float> values;  ///< one per vertex, curve or triangle
};

/// A surface, or a point set when it has no triangles.
struct ViewSurface {
  std::string id;                ///< the layer's key in the page's `layers=` query
  std::string name;              ///< shown in the panel
  std::vector<float> positions;  ///< x y z per vertex
  std::vector<std::uint32_t> triangles;
  std::vector<std::uint8_t> colours;  ///< r g b per vertex, or empty
  ViewField field;                    ///< what the layer is coloured by (no name: its colours or `colour`)
  std::string colour = "#8a9bb0";
  double opacity = 0.25;
  bool visible = false;
};

struct ViewScene {
  std::string title;
  std::vector<float> positions;  ///< medial vertices, x y z each
  std::vector<float> radii;
  std::vector<std::uint32_t> triangles;  ///< 3 per medial triangle
  std::vector<std::uint32_t> curves;     ///< 2 per medial edge that bounds no triangle
  std::vector<ViewField> fields;
  std::vector<ViewSurface> surfaces;
  std::vector<std::string> notes;  ///< what could not be shown and why, for the terminal
};

/// Reads a finished run folder; throws std::runtime_error saying what is missing and what to do.
ViewScene read_view_scene(const std::filesystem::path& run_folder);

}  // namespace medax::cli
