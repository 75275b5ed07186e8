// Shared parts of the fuzz targets: see fuzz_support.hpp.
#include "tests/fuzz/fuzz_support.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <string_view>

#include "apps/render/render_pipeline.hpp"
#include "apps/render/scene_frames.hpp"

namespace wisp::fuzz {

namespace fs = std::filesystem;

const fs::path& scratch() {
  static const fs::path dir = [] {
    const char* tmp = std::getenv("TMPDIR");
    fs::path d = fs::path(tmp && *tmp ? tmp : "/tmp") / ("wisp-fuzz-" + std::to_string(getpid()));
    fs::create_directories(d);
    std::atexit([] {
      std::error_code ec;
      fs::remove_all(scratch(), ec);
    });
    return d;
  }();
  return dir;
}

fs::path write_input(const std::string& name, const std::uint8_t* data, std::size_t size) {
  const fs::path path = scratch() / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  return path;
}

fs::path write_input(const std::string& name, const std::string& text) {
  return write_input(name, reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
}

void expect_clean(const std::uint8_t* input, std::size_t size, const std::function<void()>& body) {
  try {
    body();
  } catch (const std::exception& e) {
    const std::string what = e.what();
    static const char* const internals[] = {"basic_", "std::",  "bad_alloc", "vector::", "max_size",
                                            "cv::",   "OpenCV", "libpng",    "Assertion"};
    bool clean = !what.empty() && what.find('\n') == std::string::npos && what.size() < 2000;
    const std::string_view echoed(reinterpret_cast<const char*>(input), size);
    for (const char* word : internals)
      clean &= what.find(word) == std::string::npos || echoed.find(word) != std::string_view::npos;
    if (!clean) {
      std::fprintf(stderr, "fuzz: refusal is not one clean line: %s\n", what.c_str());
      std::abort();
    }
  }
}

io::Scene tiny(io::Scene s) {
  s.camera.width = s.camera.height = 24;
  s.hair.count = s.hair.count == 0 ? 4 : std::min(s.hair.count, 4);
  s.hair.segments = s.hair.segments == 0 ? 0 : std::min(s.hair.segments, 6);
  s.motion.duration = std::min(s.motion.duration, 1.0 / s.sim.fps);
  s.sim.preroll = 0;
  s.sim.step_rate = s.sim.fps;
  s.sim.substeps = 1;
  s.sim.iterations = 1;
  return s;
}

void render_tiny(const io::Scene& scene, const fs::path& anim) {
  render::SceneFramesOptions options;
  options.anim = anim;
  const render::SceneFrames frames = render::load_scene_frames(tiny(scene), options);
  if (frames.frame_count() == 0) return;
  const render::FrameSetup setup = render::frame_setup(frames.scene);
  render::render_frame(frames.projected[0], render::frame_body(frames, 0),
                       render::frame_occluders(frames, 0), render::frame_base(frames, 0), setup,
                       nullptr);
}

}  // namespace wisp::fuzz
