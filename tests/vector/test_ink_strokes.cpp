// Ink strokes (vector/ink_strokes.hpp): a stroke's width follows the strand (root and tip fades)
// and its ends (the taper), whatever points the arrangement happened to put along its line.
#include <catch2/catch.hpp>

#include "tests/vector/scenes.hpp"
#include "vector/ink_strokes.hpp"
#include "vector/wisp.hpp"

using namespace wisp;
using Eigen::Vector2d;

namespace {

// The stroke's width at the point of its path nearest p (the path sampled finely).
double width_near(const vector::InkCurve& c, const Vector2d& p) {
  double best = INFINITY, width = 0;
  for (int i = 0; i <= 4000; ++i) {
    const double s = i / 4000.0;
    const double d = (diffusion::eval(c, s) - p).squaredNorm();
    if (d < best) best = d, width = vector::width_at(c.width, s);
  }
  return width;
}

}  // namespace

TEST_CASE("an ink stroke's width does not depend on the points along its line", "[vector][ink]") {
  vector::WispStyle style;
  style.width = 0.02;
  const auto wisp =
      vector::build_wisp(test::straight(0, {100, 100}, {400, 100}, 2, 2, 12), 800, style);
  REQUIRE(wisp);
  vector::InkStyle ink;
  ink.occlusion_width = 3;  // root and tip fades, end tapers: the defaults

  // An occlusion line along the wisp's left side, from near the root to near the tip: once as its
  // two ends, once with many points between them (the vertices that other outlines crossing it
  // put there).
  const Vector2d a = wisp->sections.front().left + Vector2d(5, 0);
  const Vector2d b = wisp->sections.back().left - Vector2d(5, 0);
  vector::WispArrangement sparse, dense;
  sparse.occlusion.push_back({{a, b}, false, 0});
  dense.occlusion.push_back({{a}, false, 0});
  for (int i = 1; i <= 37; ++i) dense.occlusion[0].points.push_back(a + (b - a) * (i / 38.0));
  dense.occlusion[0].points.push_back(b);
  const auto one = vector::ink_curves({*wisp}, sparse, ink, 512, 512);
  const auto many = vector::ink_curves({*wisp}, dense, ink, 512, 512);
  REQUIRE(one.size() == 1);
  REQUIRE(many.size() == 1);

  double widest = 0;
  for (int i = 1; i < 30; ++i) {
    const Vector2d p = a + (b - a) * (i / 30.0);
    const double w1 = width_near(one[0], p), w2 = width_near(many[0], p);
    CHECK(std::abs(w1 - w2) <= 0.02 * ink.occlusion_width);
    // The width is the strand's fade there (no taper this far from the ends).
    const double v = vector::strand_parameter_near(*wisp, p);
    if ((p - a).norm() > 2 * ink.end_taper && (p - b).norm() > 2 * ink.end_taper)
      CHECK(w1 == Approx(ink.occlusion_width * vector::root_factor(ink, v)).margin(0.05));
    widest = std::max(widest, w1);
  }
  CHECK(widest == Approx(ink.occlusion_width).margin(0.06));  // full width between the fades
}
