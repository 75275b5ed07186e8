// Fuzz target: a toon ramp image (io/ramp_file.cpp) shading a tiny frame.
#include "io/scene.hpp"
#include "tests/fuzz/fuzz_support.hpp"
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  wisp::fuzz::write_input("ramp.png", data, size);
  const auto scene = wisp::fuzz::write_input(
      "scene.json", R"({"style": {"preset": "toon", "shading": {"ramp": "ramp.png"}}})");
  wisp::fuzz::expect_clean(data, size,
                           [&] { wisp::fuzz::render_tiny(wisp::io::load_scene(scene)); });
  return 0;
}
