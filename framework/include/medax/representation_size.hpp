#pragma once
// The size of a medial representation when it is more than the complex's spheres: MSD counts
// N_d discrete elements (#v + #e + #f) and N_c continuous parameters (Σ|V(T_P)| + 3·#v, paper §6).
// A stage that builds such a representation publishes it; the `counts` evaluation stage reports
// it instead of the complex's own count (N_c = 4 per sphere).
#include <medax/scene_data.hpp>

#include <cstddef>
#include <string>

namespace medax {

struct RepresentationSize {
  std::size_t discrete = 0;    ///< N_d
  std::size_t continuous = 0;  ///< N_c
  std::string rule;            ///< how they were counted, for reports ("MSD: N_c = Σ|V(T_P)| + 3·#v")
};

inline const DataKey<RepresentationSize> kRepresentationSize{"representation_size", "msd"};

}  // namespace medax
