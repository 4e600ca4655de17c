// Plugin discovery and loading with Boost.DLL. Loading never throws: every problem becomes one
// error line naming the file and what to do.
#include <medax/kernel/registry.hpp>

#include "suggest.hpp"

#include <boost/dll/runtime_symbol_info.hpp>
#include <boost/dll/shared_library.hpp>
#include <fmt/format.h>

#include <dlfcn.h>

#include <algorithm>
#include <cstdlib>
#include <set>

namespace medax {

namespace fs = std::filesystem;

struct Registry::Libraries {
  // Libraries are never unloaded: stage objects and factories point into their code, and
  // unloading at exit buys nothing.
  std::vector<boost::dll::shared_library*> loaded;
  std::set<std::string> file_names;  // for shadowing: first folder wins
};

Registry::Registry() : libraries_(std::make_unique<Libraries>()) {}
Registry::~Registry() = default;

std::vector<fs::path> Registry::search_path() {
  std::vector<fs::path> dirs;
  // libmedax.so lives in <prefix>/<libdir>; its plugins in <prefix>/<libdir>/medax/plugins.
  const fs::path kernel_lib(boost::dll::this_line_location().string());
  dirs.push_back(kernel_lib.parent_path().parent_path() / MEDAX_PLUGIN_SUBDIR);
  if (const char* extra = std::getenv("MEDAX_PLUGIN_PATH")) {
    std::string list(extra);
    std::size_t start = 0;
    while (start <= list.size()) {
      const std::size_t end = std::min(list.find(':', start), list.size());
      if (end > start) dirs.emplace_back(list.substr(start, end - start));
      start = end + 1;
    }
  }
  return dirs;
}

void Registry::load_default() {
  for (const fs::path& dir : search_path()) load_directory(dir);
}

void Registry::load_directory(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return;  // a missing folder on the path is not an error
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir, ec))
    if (entry.path().extension() == ".so") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  for (const fs::path& file : files) {
    if (libraries_->file_names.count(file.filename().string())) continue;  // shadowed
    load_file(file);
  }
}

namespace {
/// The dynamic loader's own words on why `file` does not load (Boost.DLL reports only an errno
/// text such as "Bad file descriptor"): usually which library it needs and cannot find.
std::string loader_message(const fs::path& file) {
  void* handle = ::dlopen(file.c_str(), RTLD_LAZY | RTLD_LOCAL);
  if (handle) {
    ::dlclose(handle);
    return "unknown reason";
  }
  const char* why = ::dlerror();
  return why ? why : "unknown reason";
}
}  // namespace

bool Registry::load_file(const fs::path& file) {
  const std::string where = fmt::format("plugin {}", file.string());
  auto library = std::make_unique<boost::dll::shared_library>();
  boost::dll::fs::error_code ec;
  library->load(file.string(), boost::dll::load_mode::rtld_lazy | boost::dll::load_mode::rtld_local, ec);
  if (ec) {
    errors_.push_back(fmt::format("{}: cannot be loaded: {}; rebuild it or remove it from the plugin path", where,
                                  loader_message(file)));
    return false;
  }
  if (!library->has("medax_plugin_entry")) {
    errors_.push_back(fmt::format("{}: not a medax plugin (no medax_plugin_entry symbol; did it use MEDAX_PLUGIN?)", where));
    return false;
  }
  const auto& entry = library->get<const PluginEntry>("medax_plugin_entry");
  if (entry.magic != kPluginMagic) {
    errors_.push_back(fmt::format("{}: medax_plugin_entry has a wrong magic number; the file is corrupt", where));
    return false;
  }
  if (entry.abi_version != kAbiVersion) {
    errors_.push_back(fmt::format("{}: built for medax ABI {} but this kernel has ABI {}; rebuild the plugin "
                                  "against medax {}",
                                  where, entry.abi_version, kAbiVersion, kVersion));
    return false;
  }
  PluginRegistrar registrar;
  try {
    entry.register_stages(registrar);
  } catch (const std::exception& e) {
    errors_.push_back(fmt::format("{}: registration failed: {}", where, e.what()));
    return false;
  }
  libraries_->file_names.insert(file.filename().string());
  add_package(PackageInfo{entry.package ? entry.package : "?", entry.version ? entry.version : "?", file},
              registrar);
  libraries_->loaded.push_back(library.release());
  return true;
}

void Registry::add_package(const PackageInfo& package, const PluginRegistrar& registrar) {
  auto shared = std::make_shared<const PackageInfo>(package);
  for (const StageEntry& entry : registrar.entries()) {
    if (const RegisteredStage* existing = find(entry.info.name)) {
      errors_.push_back(fmt::format("plugin {}: stage '{}' is already registered by {}; the later one is ignored "
                                    "(rename the stage or remove one plugin)",
                                    package.file.string(), entry.info.name, existing->package->file.string()));
      continue;
    }
    stages_.push_back(RegisteredStage{entry, shared});
  }
}

const RegisteredStage* Registry::find(std::string_view name) const {
  for (const RegisteredStage& s : stages_)
    if (s.info().name == name) return &s;
  return nullptr;
}

std::vector<std::string> Registry::suggest(std::string_view name) const {
  std::vector<std::string> names;
  for (const RegisteredStage& s : stages_) names.push_back(s.info().name);
  return detail::closest_names(name, names);
}

std::vector<const RegisteredStage*> Registry::stages() const {
  std::vector<const RegisteredStage*> out;
  for (const RegisteredStage& s : stages_) out.push_back(&s);
  std::sort(out.begin(), out.end(), [](const RegisteredStage* a, const RegisteredStage* b) {
    return std::pair(a->info().role, a->info().name) < std::pair(b->info().role, b->info().name);
  });
  return out;
}

std::unique_ptr<Stage> Registry::create(std::string_view name) const {
  const RegisteredStage* s = find(name);
  if (!s) throw std::invalid_argument(fmt::format("no stage named '{}'", name));
  return s->entry.create();
}

Registry& Registry::global() {
  static Registry* registry = [] {
    auto* r = new Registry();  // lives to the end of the process, like the libraries
    r->load_default();
    return r;
  }();
  return *registry;
}

}  // namespace medax
