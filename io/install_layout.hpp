// Where the parts of wisp are, found from the running executable, so that the build tree
// (build/bin, build/lib) and an installed copy (PREFIX/bin, PREFIX/lib) work alike, wherever they
// are: every executable (`wisp`, the command executables wisp-<command> it runs, wisp-inspect,
// wisp-bench, the tests) lives in one bin/ folder, and the modules loaded on demand in lib/wisp/
// beside it. Header-only: the `wisp` dispatcher uses it without linking any stage library.
#pragma once

#include <filesystem>
#include <string>

namespace wisp::io {

// The folder of the running executable (/proc/self/exe); empty if Linux does not say.
inline std::filesystem::path executable_dir() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::filesystem::path() : exe.parent_path();
}

// A module loaded with dlopen ("wisp-video.so"): bin/../lib/wisp/<name>.
inline std::filesystem::path module_path(const std::string& name) {
  return (executable_dir().parent_path() / "lib" / "wisp" / name).lexically_normal();
}

}  // namespace wisp::io
