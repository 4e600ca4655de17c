#include <medax/io.hpp>

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>

namespace medax {

namespace fs = std::filesystem;

namespace {

/// Flushes `path` (a file or a folder) to the disk; returns errno, or 0.
int sync_path(const fs::path& path, int flags) {
  const int fd = ::open(path.c_str(), flags | O_CLOEXEC);
  if (fd < 0) return errno;
  const int rc = ::fsync(fd) == 0 ? 0 : errno;
  ::close(fd);
  return rc;
}

/// The reason of a failed write, for a message: "No space left on device", "File too large"...
std::string cause(int err) { return err ? std::strerror(err) : "unknown error (disk full?)"; }

}  // namespace

void write_file_atomic(const fs::path& path, const std::function<void(std::ostream&)>& body) {
  static std::atomic<unsigned> counter{0};
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  const fs::path temp =
      dir / fmt::format(".{}.tmp-{}-{}", path.filename().string(), ::getpid(), counter++);
  try {
    {
      errno = 0;  // the streams keep no error code: the failed system call's errno names the cause
      std::ofstream out(temp, std::ios::binary | std::ios::trunc);
      if (!out)
        throw IoError(fmt::format("{}: cannot create file: {} (does the folder exist and is it writable?)",
                                  temp.string(), cause(errno)));
      body(out);
      out.flush();
      out.close();
      if (!out) throw IoError(fmt::format("{}: write failed: {}", path.string(), cause(errno)));
    }
    // The data reaches the disk before the name does: after a crash the target is the old
    // file or the whole new one, never an empty or torn one.
    if (const int err = sync_path(temp, O_RDONLY))
      throw IoError(fmt::format("{}: write failed while flushing to disk: {} (disk full or failing?)", path.string(),
                                std::strerror(err)));
    std::error_code ec;
    fs::rename(temp, path, ec);
    if (ec)
      throw IoError(fmt::format("{}: cannot replace it with the written file: {}", path.string(), ec.message()));
  } catch (...) {
    std::error_code ignored;
    fs::remove(temp, ignored);
    throw;
  }
  sync_path(dir, O_RDONLY | O_DIRECTORY);  // the rename itself; best effort (some file systems refuse)
}

}  // namespace medax
