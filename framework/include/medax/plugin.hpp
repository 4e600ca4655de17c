#pragma once
// Plugin registration. A plugin package is one shared library; it may register several stages:
//
//   MEDAX_PLUGIN("my_package", "1.0.0") {
//     registrar.add<MyExtraction>();
//     registrar.add<MySignificance>();
//   }
//
// Each stage class derives from one role interface (stage.hpp), has
// `static medax::StageInfo describe();` (name, summary, docs page) and declares its parameters
// in `declare()` (params.hpp).
#include <medax/stage.hpp>
#include <medax/version.hpp>

#include <functional>
#include <memory>
#include <type_traits>
#include <vector>

namespace medax {

using StageFactory = std::function<std::unique_ptr<Stage>()>;

/// Everything `medax describe` shows of a stage class: its describe(), its role, and the
/// parameters a fresh instance declares.
template <typename StageT>
StageInfo stage_info() {
  static_assert(std::is_base_of_v<Stage, StageT>, "a stage derives from a role interface");
  StageInfo info = StageT::describe();
  info.role = StageT::kRole;
  info.params = StageT().param_specs();
  return info;
}

struct StageEntry {
  StageInfo info;
  StageFactory create;
};

/// Collects the stages a plugin package offers.
class PluginRegistrar {
 public:
  template <typename StageT>
  void add() {
    entries_.push_back({stage_info<StageT>(), [] { return std::make_unique<StageT>(); }});
  }
  const std::vector<StageEntry>& entries() const { return entries_; }

 private:
  std::vector<StageEntry> entries_;
};

/// What every plugin library exports under the symbol `medax_plugin_entry`. The magic and ABI
/// stamp are checked before anything else is read.
struct PluginEntry {
  unsigned magic;          ///< kPluginMagic
  unsigned abi_version;    ///< kAbiVersion of the SDK the plugin was built against
  const char* package;     ///< package name, e.g. "voronoi"
  const char* version;     ///< package version
  void (*register_stages)(PluginRegistrar&);
};

inline constexpr unsigned kPluginMagic = 0x4D454458u;  // "MEDX"

}  // namespace medax

#define MEDAX_PLUGIN(PACKAGE, VERSION)                                                        \
  static void medax_register_stages_(::medax::PluginRegistrar& registrar);                    \
  extern "C" __attribute__((visibility("default")))                                           \
  const ::medax::PluginEntry medax_plugin_entry = {::medax::kPluginMagic, ::medax::kAbiVersion, \
                                                   PACKAGE, VERSION, &medax_register_stages_}; \
  static void medax_register_stages_([[maybe_unused]] ::medax::PluginRegistrar& registrar)
