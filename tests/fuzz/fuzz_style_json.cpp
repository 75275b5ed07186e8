// Fuzz target: a style preset file (style.preset names it), then a tiny frame in that style.
#include "io/scene.hpp"
#include "tests/fuzz/fuzz_support.hpp"
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  wisp::fuzz::write_input("style.json", data, size);
  const auto scene =
      wisp::fuzz::write_input("scene.json", R"({"style": {"preset": "style.json"}})");
  wisp::fuzz::expect_clean(data, size,
                           [&] { wisp::fuzz::render_tiny(wisp::io::load_scene(scene)); });
  return 0;
}
