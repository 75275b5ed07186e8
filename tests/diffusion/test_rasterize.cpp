// Rasterizer: sides, cut links, no leaks.
#include <catch2/catch.hpp>

#include "diffusion/rasterize.hpp"
#include "scenes.hpp"

using namespace wisp::diffusion;

TEST_CASE("a circle fixes its inside colour inside and its outside colour outside", "[rasterize]") {
  const auto c = wisp::test::circle(32, 32, 10, Color(1, 0, 0), Color(0, 0, 1));
  const Problem p = rasterize({c}, 64, 64);
  const size_t n = p.pixel_count();
  int inside = 0, outside = 0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const size_t i = p.index(x, y);
      if (!p.fixed[i]) continue;
      const double r = std::hypot(x + 0.5 - 32, y + 0.5 - 32);
      if (r < 10) {
        CHECK(p.value[i] == 1.0f);
        ++inside;
      } else {
        CHECK(p.value[2 * n + i] == 1.0f);
        ++outside;
      }
    }
  CHECK(inside > 40);
  CHECK(outside > 40);
}
