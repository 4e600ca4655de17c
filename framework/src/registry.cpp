// Plugin discovery and loading with Boost.DLL. Loading never throws: every problem becomes one
// error line naming the file and what to do.
#include <medax/kernel/registry.hpp>

#include "suggest.hpp"

#include <boost/dll/runtime_symbol_info.hpp>
#include <boost/dll/shared_library.hpp>
#include <fmt/format.h>

#include <dlfcn.h>
#include <elf.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <optional>
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

namespace {
/// Reads `count` bytes at `offset` of `in`; false when the file ends first.
bool read_at(std::ifstream& in, std::uint64_t offset, void* out, std::size_t count) {
  in.clear();
  in.seekg(static_cast<std::streamoff>(offset));
  in.read(static_cast<char*>(out), static_cast<std::streamsize>(count));
  return in.gcount() == static_cast<std::streamsize>(count);
}

/// The ELF machine of the running kernel library: a plugin must match it.
std::uint16_t own_machine() {
  static const std::uint16_t machine = [] {
    Elf64_Ehdr header{};
    std::ifstream in(boost::dll::this_line_location().string(), std::ios::binary);
    return in && read_at(in, 0, &header, sizeof header) ? header.e_machine : std::uint16_t{EM_NONE};
  }();
  return machine;
}

/// `offset + count * size` fits in `file_size` (no overflow: count and size are 16-bit, and an
/// offset past the end fails first).
bool table_fits(std::uint64_t offset, std::uint64_t count, std::uint64_t size, std::uint64_t file_size) {
  return offset <= file_size && count * size <= file_size - offset;
}

constexpr const char* kRebuildOrRemove = "rebuild it or remove it from the plugin path";

/// A plugin candidate opened for the checks below.
struct ElfFile {
  std::ifstream in;
  std::uint64_t size = 0;
  std::string truncated(const std::string& what, std::uint64_t end) const {
    return fmt::format("truncated (its {} ends at byte {} but the file has {} bytes: a copy or build was cut "
                       "short); {}",
                       what, end, size, kRebuildOrRemove);
  }
};

unsigned char own_byte_order() {
  const std::uint16_t probe = 1;
  unsigned char first = 0;
  std::memcpy(&first, &probe, 1);
  return first == 1 ? ELFDATA2LSB : ELFDATA2MSB;
}

/// Reads the ELF header; a problem when the file is no 64-bit shared library for this machine.
std::optional<std::string> header_problem(ElfFile& f, Elf64_Ehdr& header) {
  unsigned char ident[EI_NIDENT] = {};
  const bool whole_ident = read_at(f.in, 0, ident, sizeof ident);
  if (std::memcmp(ident, ELFMAG, std::min<std::uint64_t>(SELFMAG, f.size)) != 0 || f.size == 0)
    return fmt::format("not a plugin (not an ELF shared library: no ELF magic number in its {} bytes); remove it "
                       "from the plugin path",
                       f.size);
  if (!whole_ident || f.size < sizeof header || !read_at(f.in, 0, &header, sizeof header))
    return fmt::format("truncated (an ELF file of {} bytes, shorter than its {}-byte header); {}", f.size,
                       sizeof header, kRebuildOrRemove);
  if (ident[EI_CLASS] != ELFCLASS64)
    return fmt::format("not a plugin for this machine (a 32-bit ELF file; medax plugins are 64-bit); {}",
                       kRebuildOrRemove);
  if (ident[EI_DATA] != own_byte_order())
    return fmt::format("not a plugin for this machine (its byte order differs); {}", kRebuildOrRemove);
  if (header.e_machine != own_machine() && own_machine() != EM_NONE)
    return fmt::format("not a plugin for this machine (ELF machine {} but this medax is machine {}); {}",
                       header.e_machine, own_machine(), kRebuildOrRemove);
  if (header.e_type != ET_DYN)
    return fmt::format("not a plugin (ELF type {} is not a shared library; plugins are built with "
                       "medax_add_plugin); remove it from the plugin path",
                       header.e_type == ET_EXEC ? "executable" : header.e_type == ET_REL ? "object file"
                                                                 : std::to_string(header.e_type));
  return std::nullopt;
}

/// The program header table and every PT_LOAD segment lie inside the file; `loads` tells
/// whether there is any segment to load.
std::optional<std::string> segments_problem(ElfFile& f, const Elf64_Ehdr& header, bool& loads) {
  loads = false;
  if (header.e_phnum > 0 && header.e_phentsize != sizeof(Elf64_Phdr))
    return fmt::format("not a plugin (corrupt ELF header: program header size {}); {}", header.e_phentsize,
                       kRebuildOrRemove);
  if (header.e_phnum > 0 && !table_fits(header.e_phoff, header.e_phnum, header.e_phentsize, f.size))
    return f.truncated("program header table", header.e_phoff + std::uint64_t{header.e_phnum} * header.e_phentsize);
  for (std::uint16_t i = 0; i < header.e_phnum; ++i) {
    Elf64_Phdr segment{};
    if (!read_at(f.in, header.e_phoff + std::uint64_t{i} * sizeof segment, &segment, sizeof segment))
      return f.truncated("program header table", header.e_phoff + (std::uint64_t{i} + 1) * sizeof segment);
    if (segment.p_type != PT_LOAD) continue;
    loads = true;
    if (segment.p_offset > f.size || segment.p_filesz > f.size - segment.p_offset)
      return f.truncated(fmt::format("loaded segment {}", i), segment.p_offset + segment.p_filesz);
  }
  return std::nullopt;
}

/// The section header table, when there is one, lies inside the file.
std::optional<std::string> sections_problem(ElfFile& f, const Elf64_Ehdr& header) {
  if (header.e_shoff == 0) return std::nullopt;
  if (header.e_shentsize != sizeof(Elf64_Shdr))
    return fmt::format("not a plugin (corrupt ELF header: section header size {}); {}", header.e_shentsize,
                       kRebuildOrRemove);
  // e_shnum 0 with a table: the real count is in section 0's sh_size (extended numbering).
  std::uint64_t sections = header.e_shnum;
  if (sections == 0) {
    Elf64_Shdr first{};
    if (!table_fits(header.e_shoff, 1, sizeof first, f.size) || !read_at(f.in, header.e_shoff, &first, sizeof first))
      return f.truncated("section header table", header.e_shoff + sizeof first);
    sections = first.sh_size;
  }
  if (sections > f.size / sizeof(Elf64_Shdr) || !table_fits(header.e_shoff, sections, header.e_shentsize, f.size))
    return f.truncated("section header table", header.e_shoff + sections * header.e_shentsize);
  return std::nullopt;
}

/// Why `file` cannot be handed to dlopen, or nothing. The loader maps each PT_LOAD segment's
/// file range and touches it: a truncated file kills the process with SIGBUS inside dlopen, so
/// every range the loader reads is checked against the file's size first.
std::optional<std::string> elf_problem(const fs::path& file) {
  ElfFile f;
  std::error_code ec;
  f.size = fs::file_size(file, ec);
  if (ec) return fmt::format("cannot be read: {}; check that it exists and is readable", ec.message());
  f.in.open(file, std::ios::binary);
  if (!f.in) return fmt::format("cannot be opened: {}; check that it is readable", std::strerror(errno));
  Elf64_Ehdr header{};
  bool loads = false;
  if (auto problem = header_problem(f, header)) return problem;
  if (auto problem = segments_problem(f, header, loads)) return problem;
  if (auto problem = sections_problem(f, header)) return problem;
  if (!loads) return fmt::format("not a plugin (an ELF file with nothing to load); {}", kRebuildOrRemove);
  return std::nullopt;
}
}  // namespace

void Registry::fail(const fs::path& file, std::string line) {
  failed_files_.emplace_back(file, line);
  errors_.push_back(std::move(line));
}

std::vector<std::string> Registry::failures_for(std::string_view stage) const {
  std::vector<std::string> lines;
  for (const auto& [file, line] : failed_files_) {
    std::string package = file.stem().string();
    for (const std::string_view prefix : {"lib", "medax_"})
      if (package.rfind(prefix, 0) == 0) package.erase(0, prefix.size());
    const bool provides = stage == package || (stage.size() > package.size() &&
                                               stage.substr(0, package.size()) == package && stage[package.size()] == '_');
    if (provides) lines.push_back(line);
  }
  return lines;
}

bool Registry::load_file(const fs::path& file) {
  const std::string where = fmt::format("plugin {}", file.string());
  // Checked before dlopen: a truncated library crashes the loader instead of failing.
  if (const auto problem = elf_problem(file)) {
    fail(file, fmt::format("{}: {}", where, *problem));
    return false;
  }
  auto library = std::make_unique<boost::dll::shared_library>();
  boost::dll::fs::error_code ec;
  library->load(file.string(), boost::dll::load_mode::rtld_lazy | boost::dll::load_mode::rtld_local, ec);
  if (ec) {
    fail(file, fmt::format("{}: cannot be loaded: {}; rebuild it or remove it from the plugin path", where,
                                  loader_message(file)));
    return false;
  }
  if (!library->has("medax_plugin_entry")) {
    fail(file, fmt::format("{}: not a medax plugin (no medax_plugin_entry symbol; did it use MEDAX_PLUGIN?)", where));
    return false;
  }
  const auto& entry = library->get<const PluginEntry>("medax_plugin_entry");
  if (entry.magic != kPluginMagic) {
    fail(file, fmt::format("{}: medax_plugin_entry has a wrong magic number; the file is corrupt", where));
    return false;
  }
  if (entry.abi_version != kAbiVersion) {
    fail(file, fmt::format("{}: built for medax ABI {} but this kernel has ABI {}; rebuild the plugin "
                                  "against medax {}",
                                  where, entry.abi_version, kAbiVersion, kVersion));
    return false;
  }
  PluginRegistrar registrar;
  try {
    entry.register_stages(registrar);
  } catch (const std::exception& e) {
    fail(file, fmt::format("{}: registration failed: {}", where, e.what()));
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
