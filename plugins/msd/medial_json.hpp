#pragma once
// Reader for the medial-mesh JSON of the MSD authors' tool (bohanwang/MSD, `input-ma.json`), so a
// user of that tool brings M unchanged. The file is an object with
//   "vertices":  [[id, {"pos": [x, y, z], ...}], ...]
//   "edges":     [[id, {"vidx": [a, b], ...}], ...]
//   "triangles": [[id, {"vidx": [a, b, c], ...}], ...]
// plus bookkeeping ("edge-vid-to-edge-id", "vtx-counter", ...) that is not needed here. Ids are
// keys, not positions. A coordinate is a number, a string holding an exact rational ("p/q" or an
// integer, decimal) or such a string as an array of character codes padded with zeros (how the
// authors' code writes GMP rationals).
#include <medax/medial_complex.hpp>

#include <filesystem>
#include <string>

namespace medax::msd {

/// M from the authors' JSON: centres, edges (every listed edge, triangle sides included) and
/// triangles; radii are 0 (the format has none). Throws std::runtime_error naming the file, the
/// position (byte offset, or the entry) and the reason when the file is malformed.
MedialComplex read_medial_json(const std::filesystem::path& file);

/// The same from text; `name` stands for the file in messages.
MedialComplex parse_medial_json(const std::string& text, const std::string& name);

}  // namespace medax::msd
