// DiffusionCurve: colour interpolation and validation.
#include <catch2/catch.hpp>

#include "diffusion/diffusion_curve.hpp"

using namespace wisp::diffusion;

TEST_CASE("colour stops interpolate linearly and clamp outside", "[curve]") {
  const std::vector<ColorStop> stops = {{0.25, Color(0, 0, 0)}, {0.75, Color(1, 0.5f, 0)}};
  CHECK(color_at(stops, 0.0).isApprox(Color(0, 0, 0)));
  CHECK(color_at(stops, 0.5).isApprox(Color(0.5f, 0.25f, 0)));
  CHECK(color_at(stops, 1.0).isApprox(Color(1, 0.5f, 0)));
  CHECK(blur_at({{0, 0.0f}, {1, 4.0f}}, 0.25) == Approx(1.0f));
}

TEST_CASE("malformed curves are rejected with the curve named", "[curve]") {
  DiffusionCurve c;
  c.points = {{0, 0}, {1, 1}};
  CHECK_THROWS_WITH(validate(c, "drawing.xml: curve 3"),
                    Catch::Contains("curve 3") && Catch::Contains("3k+1"));
  c.points = {{0, 0}, {1, 1}, {2, 2}, {3, std::nan("")}};
  CHECK_THROWS_WITH(validate(c, "c"), Catch::Contains("not a finite number"));
  c.points[3].y() = 3;
  c.left = {{0.5, Color(0, 0, 0)}, {0.2, Color(0, 0, 0)}};
  CHECK_THROWS_WITH(validate(c, "c"), Catch::Contains("not sorted"));
  c.left = {{1.5, Color(0, 0, 0)}};
  CHECK_THROWS_WITH(validate(c, "c"), Catch::Contains("outside [0,1]"));
  c.left = {};
  c.blur = {{0, -1.0f}};
  CHECK_THROWS_WITH(validate(c, "c"), Catch::Contains(">= 0"));
}
