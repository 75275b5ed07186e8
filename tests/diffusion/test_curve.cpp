// DiffusionCurve: colour interpolation and validation; Bezier flattening.
#include <catch2/catch.hpp>

#include "diffusion/bezier.hpp"
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

TEST_CASE("flattening stays within tolerance and keeps the path parameter", "[curve]") {
  const std::vector<Eigen::Vector2d> pts = {{0, 0},   {10, 30}, {40, -20}, {50, 10},
                                            {60, 40}, {70, 0},  {80, 5}};
  const auto poly = flatten_path(pts, 0.01);
  REQUIRE(poly.size() > 20);
  CHECK(poly.front().t == 0.0);
  CHECK(poly.back().t == 1.0);
  CHECK(poly.back().p == pts.back());
  for (size_t i = 1; i < poly.size(); ++i) {
    CHECK(poly[i].t > poly[i - 1].t);
    // The midpoint of each chord is close to the curve at the midpoint parameter.
    const double tm = 0.5 * (poly[i].t + poly[i - 1].t);
    const int seg = std::min(1, int(tm * 2));
    const Eigen::Vector2d on_curve = eval_cubic(&pts[3 * seg], tm * 2 - seg);
    CHECK((0.5 * (poly[i].p + poly[i - 1].p) - on_curve).norm() < 0.05);
  }
}
