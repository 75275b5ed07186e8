// Where the parts of wisp are, and the modules it loads on demand. Every executable (`wisp`, the
// command executables wisp-<command> it runs, wisp-inspect, wisp-bench, the tests) lives in one
// bin/ folder, and the modules loaded with dlopen in lib/wisp/ beside it, found from the running
// executable so that the build tree (build/bin, build/lib) and an installed copy (PREFIX/bin,
// PREFIX/lib) work alike, wherever they are. A module keeps a heavy library (FFmpeg, OpenCV) out
// of every command that does not use it: a command maps it only when it first needs it.
// Header-only and below every stage, so that any stage (and the `wisp` dispatcher, which links
// none) can use it.
#pragma once

#include <dlfcn.h>

#include <filesystem>
#include <string>

namespace wisp::util {

// The folder of the running executable (/proc/self/exe); empty if Linux does not say.
inline std::filesystem::path executable_dir() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::filesystem::path() : exe.parent_path();
}

// A module's file ("wisp-video.so"): bin/../lib/wisp/<name>.
inline std::filesystem::path module_path(const std::string& name) {
  return (executable_dir().parent_path() / "lib" / "wisp" / name).lexically_normal();
}

// A module opened for good (never closed: the libraries it pulls in keep state past a dlclose),
// or why it could not be.
struct Module {
  void* handle = nullptr;
  std::filesystem::path path;
  std::string error;  // empty when open

  // The function `name` of the module as F, or null (setting `error`) when it lacks it: a module
  // from another build.
  template <class F>
  F function(const char* name) {
    void* f = handle ? dlsym(handle, name) : nullptr;
    if (!f && error.empty())
      error = "the module " + path.string() + " lacks " + name + " (from another build?)";
    return reinterpret_cast<F>(f);
  }
};

// Opens lib/wisp/<file>; `what` names it in the error ("video": "cannot load the video module").
inline Module open_module(const std::string& file, const std::string& what) {
  Module m;
  m.path = module_path(file);
  m.handle = dlopen(m.path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!m.handle) {
    const char* why = dlerror();
    m.error = "cannot load the " + what + " module (" + (why ? why : m.path.string()) +
              "); build or install wisp whole";
  }
  return m;
}

}  // namespace wisp::util
