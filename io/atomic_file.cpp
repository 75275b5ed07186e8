// write_atomically: see atomic_file.hpp.
#include "io/atomic_file.hpp"

#include <unistd.h>

#include <stdexcept>
#include <string>
#include <system_error>

namespace wisp::io {

void write_atomically(const std::filesystem::path& path,
                      const std::function<void(const std::filesystem::path& tmp)>& write) {
  namespace fs = std::filesystem;
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw std::runtime_error(path.string() + ": output folder '" + dir.string() +
                             "' does not exist");
  if (access(dir.c_str(), W_OK) != 0)
    throw std::runtime_error(path.string() + ": output folder '" + dir.string() +
                             "' is not writable");
  const fs::path tmp = dir / ("." + path.stem().string() + ".partial-" + std::to_string(getpid()) +
                              path.extension().string());
  try {
    write(tmp);
  } catch (...) {
    fs::remove(tmp, ec);
    throw;
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw std::runtime_error(path.string() + ": cannot move the finished file into place");
  }
}

}  // namespace wisp::io
