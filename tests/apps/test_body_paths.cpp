// The body's tone regions (apps/render/body_paths.hpp) on a flat mesh whose levels are known in
// closed form: the areas of the lit and shadow fills against the exact ones.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "apps/render/body_paths.hpp"

namespace {

using Eigen::Vector2d;
using wisp::render::BodyPath;

// The area inside a closed cubic Bezier loop (points P0, then C1 C2 P per piece), from 64
// samples a piece: far within the tolerances below for these gently curved outlines.
double loop_area(const std::vector<Vector2d>& p) {
  double twice = 0;
  Vector2d prev = p[0];
  for (size_t i = 0; i + 3 < p.size(); i += 3)
    for (int k = 1; k <= 64; ++k) {
      const double t = k / 64.0, s = 1 - t;
      const Vector2d q = s * s * s * p[i] + 3 * s * s * t * p[i + 1] + 3 * s * t * t * p[i + 2] +
                         t * t * t * p[i + 3];
      twice += prev.x() * q.y() - prev.y() * q.x();
      prev = q;
    }
  return 0.5 * twice;
}

double path_area(const BodyPath& path) {
  double a = 0;
  for (const auto& loop : path.loops) a += loop_area(loop);
  return std::abs(a);
}

// A 40 x 40 px square from (10, 10) of 2 px cells, two triangles each, turning one way; the
// shade rises 0.01 a pixel along x, so the terminator (shade 0.45) is the line x = 30.5, and
// `clearance(x)` per vertex.
template <class Clearance>
wisp::sim::ProjectedBody square(Clearance&& clearance) {
  wisp::sim::ProjectedSurface s;
  s.part = wisp::sim::kBodyTorso;
  constexpr int n = 21;  // vertices a side
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x = 10 + 2 * i, y = 10 + 2 * j;
      s.pixel.emplace_back(x, y);
      s.shade.push_back(float(0.45 + 0.01 * (x - 30.5)));
      s.clearance.push_back(float(clearance(x)));
      s.local.emplace_back(x, y, 0);
    }
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const int v = j * n + i;
      s.triangles.emplace_back(v, v + 1, v + n + 1);
      s.triangles.emplace_back(v, v + n + 1, v + n);
    }
  wisp::sim::ProjectedBody body;
  body.surfaces.push_back(std::move(s));
  return body;
}

}  // namespace

TEST_CASE("the lit fill reaches the overlap under the shadow, the shadow fill is the shadow",
          "[body_paths]") {
  wisp::render::BodyTones tones;
  tones.threshold = 0.45f;
  tones.overlap = 5;  // the offset's zero is x = 25.5: two columns of cells lie wholly inside it
  SECTION("nothing drawn before") {
    const auto paths = wisp::render::body_paths(
        square([](double) { return std::numeric_limits<double>::infinity(); }), tones);
    REQUIRE(paths.size() == 2);
    REQUIRE_FALSE(paths[0].shadow);
    REQUIRE(paths[1].shadow);
    // Lit: x >= 30.5 - 5; shadow: x < 30.5; 40 px tall.
    CHECK(path_area(paths[0]) == Approx((50 - 25.5) * 40).margin(0.5));
    CHECK(path_area(paths[1]) == Approx((30.5 - 10) * 40).margin(0.5));
  }
  SECTION("a solid drawn before hides the surface left of x = 15") {
    const auto paths = wisp::render::body_paths(square([](double x) { return x - 15; }), tones);
    REQUIRE(paths.size() == 2);
    CHECK(path_area(paths[0]) == Approx((50 - 25.5) * 40).margin(0.5));
    CHECK(path_area(paths[1]) == Approx((30.5 - 15) * 40).margin(0.5));
  }
  SECTION("all lit") {
    tones.threshold = 0.1f;
    const auto paths = wisp::render::body_paths(square([](double x) { return x - 15; }), tones);
    REQUIRE(paths.size() == 1);
    CHECK(path_area(paths[0]) == Approx((50 - 15) * 40).margin(0.5));
  }
}
