#include <medax/io.hpp>

#include <fmt/format.h>
#include <unistd.h>

#include <atomic>
#include <fstream>

namespace medax {

namespace fs = std::filesystem;

void write_file_atomic(const fs::path& path, const std::function<void(std::ostream&)>& body) {
  static std::atomic<unsigned> counter{0};
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  const fs::path temp =
      dir / fmt::format(".{}.tmp-{}-{}", path.filename().string(), ::getpid(), counter++);
  try {
    {
      std::ofstream out(temp, std::ios::binary | std::ios::trunc);
      if (!out) throw IoError(fmt::format("{}: cannot create file (does the folder exist and is it writable?)", temp.string()));
      body(out);
      out.flush();
      if (!out) throw IoError(fmt::format("{}: write failed (disk full?)", path.string()));
    }
    fs::rename(temp, path);
  } catch (...) {
    std::error_code ignored;
    fs::remove(temp, ignored);
    throw;
  }
}

}  // namespace medax
