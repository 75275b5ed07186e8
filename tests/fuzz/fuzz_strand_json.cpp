// Fuzz target: our JSON strand format (io/hair_json.cpp) as a scene's hair, then a tiny frame.
#include "io/scene.hpp"
#include "tests/fuzz/fuzz_support.hpp"
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  wisp::fuzz::write_input("strands.json", data, size);
  const auto scene = wisp::fuzz::write_input(
      "scene.json", R"({"hair": {"source": "json", "file": "strands.json", "count": 0}})");
  wisp::fuzz::expect_clean(data, size,
                           [&] { wisp::fuzz::render_tiny(wisp::io::load_scene(scene)); });
  return 0;
}
