// A package stamped with an ABI this kernel does not have: the registry must refuse it before
// calling anything in it.
#include <medax/plugin.hpp>

#include <stdexcept>

namespace {
void register_stages(medax::PluginRegistrar&) {
  throw std::logic_error("a package with a wrong ABI stamp must never be registered");
}
}  // namespace

extern "C" __attribute__((visibility("default")))
const medax::PluginEntry medax_plugin_entry = {medax::kPluginMagic, medax::kAbiVersion + 1000,
                                               "kernel_test_bad_abi", "0.0.1", &register_stages};
