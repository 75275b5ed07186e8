// Fuzz target: a whole tiny frame from fuzzed strand positions. The bytes become one frame of
// up to 8 guides of up to 10 samples around the default head (int16 pairs of bytes as points
// within 0.6 m of it), saved as an animation and rendered at 24x24: projection, wisps, the
// arrangement, ink, the solve and the picture see positions no simulation would produce.
#include <algorithm>

#include "io/anim_file.hpp"
#include "io/scene.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 2) return 0;
  const int strands = 1 + data[0] % 8, samples = 2 + data[1] % 9;
  std::size_t at = 2;
  const auto next = [&]() {
    if (at + 2 > size) return 0.0;
    const auto v = std::int16_t(data[at] | (data[at + 1] << 8));
    at += 2;
    return 0.6 * v / 32768.0;
  };
  wisp::sim::Animation anim;
  wisp::sim::StrandFrame frame;
  for (int s = 0; s < strands; ++s) {
    wisp::sim::Polyline p;
    for (int k = 0; k < samples; ++k) {
      const double x = next(), y = next(), z = next();
      p.emplace_back(x, y, z);
    }
    frame.strands.push_back(p);
  }
  anim.frames.push_back(frame);
  const auto path = wisp::fuzz::scratch() / "frame.wsim";
  wisp::io::write_animation(path, anim);
  const auto scene = wisp::fuzz::write_input("scene.json", "{}");
  wisp::fuzz::expect_clean(data, size,
                           [&] { wisp::fuzz::render_tiny(wisp::io::load_scene(scene), path); });
  return 0;
}
