// Fuzz target: a saved animation (io/anim_file.cpp), its first frame rendered tiny.
#include "io/scene.hpp"
#include "tests/fuzz/fuzz_support.hpp"
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto anim = wisp::fuzz::write_input("anim.wsim", data, size);
  const auto scene = wisp::fuzz::write_input("scene.json", "{}");
  wisp::fuzz::expect_clean(data, size,
                           [&] { wisp::fuzz::render_tiny(wisp::io::load_scene(scene), anim); });
  return 0;
}
