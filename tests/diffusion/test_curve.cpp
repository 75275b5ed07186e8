// DiffusionCurve: colour interpolation and validation.
#include <catch2/catch.hpp>

#include "diffusion/diffusion_curve.hpp"

using namespace wisp::diffusion;

TEST_CASE("colour stops interpolate linearly and clamp outside", "[curve]") {
  const std::vector<ColorStop> stops = {{0.25, Color(0, 0, 0)}, {0.75, Color(1, 0.5f, 0)}};
  CHECK(color_at(stops, 0.0).isApprox(Color(0, 0, 0)));
  CHECK(color_at(stops, 0.5).isApprox(Color(0.5f, 0.25f, 0)));
  CHECK(color_at(stops, 1.0).isApprox(Color(1, 0.5f, 0)));
}
