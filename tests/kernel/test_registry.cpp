// Plugin registry: loading, listing order, one clear error line per broken plugin, shadowing
// and name suggestions.
#include "kernel_test_support.hpp"

#include <medax/kernel/registry.hpp>

#include <elf.h>

#include <cstdlib>
#include <cstring>

using namespace medax;
using medax::test::plugin_dir;
using medax::test::read_text;
using medax::test::scratch_dir;
using medax::test::write_text;
namespace fs = std::filesystem;

namespace {

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

/// Loads one case folder into a fresh registry and returns its single error line.
std::string single_error(const std::string& case_name) {
  Registry registry;
  registry.load_directory(plugin_dir(case_name));
  REQUIRE(registry.errors().size() == 1);
  CHECK(registry.stages().empty());
  return registry.errors().front();
}

const fs::path kGoodFile = plugin_dir("good") / "libmedax_kernel_test_good.so";

/// A folder holding `bytes` as libmedax_broken.so beside a copy of the good package.
fs::path folder_with_broken(const std::string& name, const std::string& bytes) {
  const fs::path dir = scratch_dir("registry_" + name);
  write_text(dir / "libmedax_broken.so", bytes);
  fs::copy_file(kGoodFile, dir / kGoodFile.filename());
  return dir;
}

/// Loads `dir`: the broken file gives one error line naming it, the good package loads whole.
std::string broken_error(const fs::path& dir) {
  Registry registry;
  registry.load_directory(dir);
  REQUIRE(registry.errors().size() == 1);
  CHECK(registry.stages().size() == 9);
  CHECK(registry.find("test_scale"));
  const std::string error = registry.errors().front();
  CHECK(contains(error, "plugin " + (dir / "libmedax_broken.so").string() + ": "));
  CHECK(error.find('\n') == std::string::npos);
  return error;
}

template <class T>
T header_at(const std::string& bytes, std::size_t offset) {
  REQUIRE(offset + sizeof(T) <= bytes.size());
  T value;
  std::memcpy(&value, bytes.data() + offset, sizeof(T));
  return value;
}

}  // namespace

TEST_CASE("registry loads every stage of the good package with its package info", "[registry]") {
  Registry registry;
  registry.load_directory(plugin_dir("good"));
  REQUIRE(registry.errors().empty());
  REQUIRE(registry.stages().size() == 9);

  const RegisteredStage* scale = registry.find("test_scale");
  REQUIRE(scale);
  CHECK(scale->info().role == Role::Conditioning);
  CHECK(scale->package->name == "kernel_test");
  CHECK(scale->package->version == "1.2.3");
  CHECK(scale->package->file == plugin_dir("good") / "libmedax_kernel_test_good.so");
  REQUIRE(scale->info().params.size() == 2);
  CHECK(scale->info().params[0].name == "factor");
  CHECK(scale->info().params[1].name == "sample");
  CHECK(registry.find("test_centroid")->info().role == Role::Extraction);
  CHECK(registry.find("test_count")->info().role == Role::Evaluation);
  CHECK(registry.find("no_such_stage") == nullptr);

  auto stage = registry.create("test_centroid");
  REQUIRE(stage);
  CHECK(dynamic_cast<ExtractionStage*>(stage.get()) != nullptr);
  CHECK_THROWS_AS(registry.create("no_such_stage"), std::invalid_argument);
}

TEST_CASE("registry lists stages ordered by role then name", "[registry]") {
  Registry registry;
  registry.load_directory(plugin_dir("good"));
  std::vector<std::string> names;
  for (const RegisteredStage* s : registry.stages()) names.push_back(s->info().name);
  CHECK(names == std::vector<std::string>{"test_scale",                                   // conditioning
                                          "test_centroid", "test_oracle_centroid",        // extraction
                                          "test_publish", "test_radius_field",            // significance
                                          "test_fail",                                    // simplification
                                          "test_consume", "test_count", "test_random"});  // evaluation
}

TEST_CASE("a plugin with a wrong ABI stamp gives one error line and registers nothing", "[registry]") {
  const std::string error = single_error("bad_abi");
  CHECK(contains(error, (plugin_dir("bad_abi") / "libmedax_kernel_test_bad_abi.so").string()));
  CHECK(contains(error, "ABI " + std::to_string(kAbiVersion + 1000)));
  CHECK(contains(error, "rebuild"));
}

TEST_CASE("a text file named .so gives one error line", "[registry]") {
  const std::string error = single_error("corrupt");
  CHECK(contains(error, (plugin_dir("corrupt") / "libmedax_kernel_test_corrupt.so").string()));
  CHECK(contains(error, "not a plugin (not an ELF shared library"));
  CHECK(contains(error, "remove it from the plugin path"));
}

TEST_CASE("a library the loader refuses gives the loader's own words", "[registry]") {
  // A whole, well-formed copy of the good package that needs a library nobody has: its
  // DT_NEEDED name libmedax.so.N renamed (same length) to libmedaz.so.N.
  std::string bytes = read_text(kGoodFile);
  const std::size_t at = bytes.find("libmedax.so.");
  REQUIRE(at != std::string::npos);
  bytes[at + 7] = 'z';
  const std::string error = broken_error(folder_with_broken("loader_refuses", bytes));
  CHECK(contains(error, "cannot be loaded: libmedaz.so."));
  CHECK(contains(error, "No such file or directory"));  // dlerror's text, not an errno text alone
}

TEST_CASE("a truncated plugin is refused before dlopen and the rest still loads", "[registry]") {
  // Before the check, dlopen of a copy cut inside a loaded segment died with SIGBUS.
  const std::string good = read_text(kGoodFile);
  const auto ehdr = header_at<Elf64_Ehdr>(good, 0);
  std::vector<Elf64_Phdr> loads;
  for (std::size_t i = 0; i < ehdr.e_phnum; ++i) {
    const auto phdr = header_at<Elf64_Phdr>(good, ehdr.e_phoff + i * sizeof(Elf64_Phdr));
    if (phdr.p_type == PT_LOAD && phdr.p_filesz > 0) loads.push_back(phdr);
  }
  REQUIRE(loads.size() >= 2);
  const std::size_t in_segment = loads[1].p_offset + loads[1].p_filesz / 2;
  REQUIRE(in_segment < ehdr.e_shoff);

  SECTION("cut inside the ELF header") {
    const std::string error = broken_error(folder_with_broken("cut_header", good.substr(0, 40)));
    CHECK(contains(error, "truncated (an ELF file of 40 bytes, shorter than its 64-byte header)"));
    CHECK(contains(error, "rebuild it or remove it from the plugin path"));
  }
  SECTION("cut inside the program header table") {
    const std::size_t cut = ehdr.e_phoff + sizeof(Elf64_Phdr) + 10;
    const std::string error = broken_error(folder_with_broken("cut_phdrs", good.substr(0, cut)));
    CHECK(contains(error, "truncated (its program header table ends at byte " +
                                      std::to_string(ehdr.e_phoff + ehdr.e_phnum * sizeof(Elf64_Phdr)) +
                                      " but the file has " + std::to_string(cut) + " bytes"));
  }
  SECTION("cut inside a loaded segment") {
    const std::string error = broken_error(folder_with_broken("cut_segment", good.substr(0, in_segment)));
    CHECK(contains(error, "truncated (its loaded segment "));
    CHECK(contains(error, "ends at byte " + std::to_string(loads[1].p_offset + loads[1].p_filesz) + " but the file has " +
                                      std::to_string(in_segment) + " bytes: a copy or build was cut short"));
  }
  SECTION("cut inside a loaded segment of a file without section headers") {
    std::string bytes = good.substr(0, in_segment);
    Elf64_Ehdr stripped = ehdr;
    stripped.e_shoff = 0;
    stripped.e_shnum = 0;
    stripped.e_shstrndx = 0;
    std::memcpy(bytes.data(), &stripped, sizeof stripped);
    CHECK(contains(broken_error(folder_with_broken("cut_segment_no_sections", bytes)), "truncated (its loaded segment "));
  }
  SECTION("cut inside the section header table (the last byte missing)") {
    const std::string error = broken_error(folder_with_broken("cut_sections", good.substr(0, good.size() - 1)));
    CHECK(contains(error, "truncated (its section header table ends at byte " + std::to_string(good.size()) +
                                      " but the file has " + std::to_string(good.size() - 1) + " bytes"));
  }
}

TEST_CASE("an ELF file for another machine, of another class or not a library is refused by name", "[registry]") {
  const std::string good = read_text(kGoodFile);
  const auto patched = [&](auto&& change) {
    std::string bytes = good;
    auto header = header_at<Elf64_Ehdr>(bytes, 0);
    change(header);
    std::memcpy(bytes.data(), &header, sizeof header);
    return bytes;
  };
  CHECK(contains(broken_error(folder_with_broken("elf32", patched([](Elf64_Ehdr& h) { h.e_ident[EI_CLASS] = ELFCLASS32; }))),
                 "not a plugin for this machine (a 32-bit ELF file"));
  const auto other = header_at<Elf64_Ehdr>(good, 0).e_machine == EM_AARCH64 ? EM_X86_64 : EM_AARCH64;
  CHECK(contains(broken_error(folder_with_broken("machine", patched([&](Elf64_Ehdr& h) { h.e_machine = other; }))),
                 "not a plugin for this machine (ELF machine " + std::to_string(other) + " but"));
  CHECK(contains(broken_error(folder_with_broken("object", patched([](Elf64_Ehdr& h) { h.e_type = ET_REL; }))),
                 "not a plugin (ELF type object file is not a shared library"));
}

TEST_CASE("a library without medax_plugin_entry gives one error line", "[registry]") {
  const std::string error = single_error("no_entry");
  CHECK(contains(error, (plugin_dir("no_entry") / "libmedax_kernel_test_no_entry.so").string()));
  CHECK(contains(error, "medax_plugin_entry"));
}

TEST_CASE("a missing plugin file gives one error line and a missing folder is skipped", "[registry]") {
  Registry registry;
  const auto missing = plugin_dir("good") / "libmedax_does_not_exist.so";
  CHECK_FALSE(registry.load_file(missing));
  REQUIRE(registry.errors().size() == 1);
  CHECK(contains(registry.errors()[0], missing.string()));
  registry.load_directory(plugin_dir("no_such_case_folder"));
  CHECK(registry.errors().size() == 1);
}

TEST_CASE("a duplicate stage name is reported once and the first registration wins", "[registry]") {
  Registry registry;
  registry.load_directory(plugin_dir("good"));
  registry.load_directory(plugin_dir("duplicate"));
  REQUIRE(registry.errors().size() == 1);
  const std::string& error = registry.errors()[0];
  CHECK(contains(error, (plugin_dir("duplicate") / "libmedax_kernel_test_duplicate.so").string()));
  CHECK(contains(error, "'test_centroid'"));
  CHECK(contains(error, "already registered"));
  CHECK(registry.find("test_centroid")->package->name == "kernel_test");
  // The duplicate package's other stage is still available.
  REQUIRE(registry.find("test_duplicate_own"));
  CHECK(registry.find("test_duplicate_own")->package->name == "kernel_test_duplicate");
}

TEST_CASE("loading every broken case together gives one error per broken file", "[registry]") {
  Registry registry;
  for (const char* dir : {"good", "bad_abi", "corrupt", "no_entry", "duplicate"})
    registry.load_directory(plugin_dir(dir));
  CHECK(registry.errors().size() == 4);
  CHECK(registry.stages().size() == 10);  // 9 good + the duplicate package's own stage
}

TEST_CASE("a plugin file in an earlier folder shadows a file of the same name in a later one", "[registry]") {
  // tests/plugins/shadow holds a copy of the good package under the same file name.
  SECTION("good first: the copy is skipped without a duplicate error") {
    Registry registry;
    registry.load_directory(plugin_dir("good"));
    registry.load_directory(plugin_dir("shadow"));
    CHECK(registry.errors().empty());
    CHECK(registry.stages().size() == 9);
    CHECK(registry.find("test_scale")->package->file.parent_path() == plugin_dir("good"));
  }
  SECTION("shadow first: the copy is the one used") {
    Registry registry;
    registry.load_directory(plugin_dir("shadow"));
    registry.load_directory(plugin_dir("good"));
    CHECK(registry.errors().empty());
    CHECK(registry.find("test_scale")->package->file.parent_path() == plugin_dir("shadow"));
  }
}

TEST_CASE("search path is the kernel plugin folder then MEDAX_PLUGIN_PATH entries", "[registry]") {
  ::setenv("MEDAX_PLUGIN_PATH", "/tmp/medax-a::/tmp/medax-b", 1);
  const auto dirs = Registry::search_path();
  ::unsetenv("MEDAX_PLUGIN_PATH");
  REQUIRE(dirs.size() == 3);
  CHECK(dirs[0] == std::filesystem::path(MEDAX_BINARY_DIR) / "lib" / "medax" / "plugins");
  CHECK(dirs[1] == "/tmp/medax-a");
  CHECK(dirs[2] == "/tmp/medax-b");
}

TEST_CASE("suggest() offers the closest registered names best first", "[registry]") {
  const Registry& registry = medax::test::good_registry();
  const auto typo = registry.suggest("test_centriod");
  REQUIRE_FALSE(typo.empty());
  CHECK(typo.front() == "test_centroid");
  CHECK(typo.size() <= 3);
  const auto prefix = registry.suggest("oracle");
  REQUIRE_FALSE(prefix.empty());
  CHECK(prefix.front() == "test_oracle_centroid");
  CHECK(registry.suggest("completely_unrelated_words").empty());
}

TEST_CASE("failures_for names the failed file that may have provided a stage", "[registry]") {
  const fs::path dir = folder_with_broken("failures_for", "not a shared library\n");
  Registry registry;
  registry.load_directory(dir);
  REQUIRE(registry.errors().size() == 1);
  // libmedax_broken.so would provide `broken` and `broken_*`.
  CHECK(registry.failures_for("broken") == registry.errors());
  CHECK(registry.failures_for("broken_dual") == registry.errors());
  CHECK(registry.failures_for("brokenness").empty());
  CHECK(registry.failures_for("test_scale").empty());
}
