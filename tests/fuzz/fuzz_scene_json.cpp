// Fuzz target: a scene file (io/scene_json.cpp), then a tiny frame of the scene it describes.
#include "io/scene.hpp"
#include "tests/fuzz/fuzz_support.hpp"
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = wisp::fuzz::write_input("scene.json", data, size);
  wisp::fuzz::expect_clean(data, size,
                           [&] { wisp::fuzz::render_tiny(wisp::io::load_scene(path)); });
  return 0;
}
