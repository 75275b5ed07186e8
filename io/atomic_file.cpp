// write_atomically: see atomic_file.hpp.
#include "io/atomic_file.hpp"

#include <unistd.h>

#include <fstream>
#include <stdexcept>
#include <string>
#include <system_error>

namespace wisp::io {

void check_writable(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::error_code ec;
  if (fs::is_directory(path, ec))
    throw std::runtime_error(path.string() + ": is a folder; expected a file name");
  if (!fs::is_directory(dir, ec))
    throw std::runtime_error(path.string() + ": output folder '" + dir.string() +
                             "' does not exist");
  if (access(dir.c_str(), W_OK) != 0)
    throw std::runtime_error(path.string() + ": output folder '" + dir.string() +
                             "' is not writable");
}

void write_atomically(const std::filesystem::path& path,
                      const std::function<void(const std::filesystem::path& tmp)>& write) {
  namespace fs = std::filesystem;
  check_writable(path);
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::error_code ec;
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

void write_text_atomically(const std::filesystem::path& path, const std::string& text) {
  write_atomically(path, [&](const std::filesystem::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out << text;
    if (!out.flush()) throw std::runtime_error(path.string() + ": write failed");
  });
}

}  // namespace wisp::io
