// Fuzz target: Cem Yuksel's .hair format (io/hair_file.cpp) as a scene's hair, then a tiny frame.
#include "io/scene.hpp"
#include "tests/fuzz/fuzz_support.hpp"
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  wisp::fuzz::write_input("model.hair", data, size);
  const auto scene = wisp::fuzz::write_input(
      "scene.json", R"({"hair": {"source": "hair", "file": "model.hair", "count": 0}})");
  wisp::fuzz::expect_clean(data, size,
                           [&] { wisp::fuzz::render_tiny(wisp::io::load_scene(scene)); });
  return 0;
}
