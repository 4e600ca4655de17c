#pragma once
// A closed surface that a stage rebuilds from its medial representation (MSD's Ŝ, the union of
// its primitives), published for the evaluation stages: when the scene holds one,
// `reconstruction` measures it against the shape instead of the medial envelope.
//
//   ctx.data().publish(kReconstructedSurface, std::move(rebuilt), ctx.stage_id());  // msd
//   if (const auto* s = ctx.data().find(kReconstructedSurface)) ...                 // reconstruction
#include <medax/geometry.hpp>
#include <medax/scene_data.hpp>
#include <medax/surface.hpp>

#include <ostream>
#include <string>

namespace medax {

struct ReconstructedSurface {
  SurfaceMesh surface;   ///< closed and oriented, in the working frame
  Similarity to_input;   ///< working frame → input frame (the run folder's file is in the input frame)
  std::string method;    ///< how it was built, for logs and reports ("signed distance 256^3", ...)
};

/// Writes the surface as OFF in the input frame.
inline void write_reconstructed_surface_off(const ReconstructedSurface& rebuilt, std::ostream& out) {
  const auto precision = out.precision(17);
  out << "OFF\n" << rebuilt.surface.vertices.size() << ' ' << rebuilt.surface.faces.size() << " 0\n";
  for (const Vec3& v : rebuilt.surface.vertices) {
    const Vec3 p = rebuilt.to_input.apply(v);
    out << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
  }
  for (const Tri& f : rebuilt.surface.faces) out << "3 " << f[0] << ' ' << f[1] << ' ' << f[2] << '\n';
  out.precision(precision);
}

inline const DataKey<ReconstructedSurface> kReconstructedSurface{"reconstructed_surface", "msd", "reconstruction.off",
                                                                 write_reconstructed_surface_off};

}  // namespace medax
