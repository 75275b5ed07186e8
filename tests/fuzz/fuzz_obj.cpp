// Fuzz target: an OBJ head mesh (io/scene_mesh.cpp), simulated against and drawn in a tiny frame.
#include "io/scene.hpp"
#include "tests/fuzz/fuzz_support.hpp"
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  wisp::fuzz::write_input("head.obj", data, size);
  const auto scene =
      wisp::fuzz::write_input("scene.json", R"({"head": {"shape": "mesh", "mesh": "head.obj"}})");
  wisp::fuzz::expect_clean(data, size,
                           [&] { wisp::fuzz::render_tiny(wisp::io::load_scene(scene)); });
  return 0;
}
