// Rasterizer: every pixel next to a curve is anchored to (or, in the first-order mode, fixed to)
// the colour of the side it lies on, crossed links are cut so that no colour leaks through a
// curve, Neumann sides constrain nothing (and, when opaque, hide what lies behind them on a link);
// the anchors make a second-order boundary.
#include <catch2/catch.hpp>
#include <queue>

#include "diffusion/multigrid.hpp"
#include "diffusion/rasterize.hpp"
#include "diffusion/reference.hpp"
#include "scenes.hpp"

using namespace wisp::diffusion;
using wisp::test::circle;

namespace {

// Signed side of point q relative to the flattened curve: > 0 on the left, (-d.y, d.x).
double side_of(const DiffusionCurve& c, const Eigen::Vector2d& q) {
  const auto poly = flatten(c, 0.001);
  double best = 1e18, side = 0;
  for (size_t k = 1; k < poly.size(); ++k) {
    const Eigen::Vector2d a = poly[k - 1].p, d = poly[k].p - a;
    const double len2 = d.squaredNorm();
    const double s = len2 > 0 ? std::clamp((q - a).dot(d) / len2, 0.0, 1.0) : 0.0;
    const double dist = (a + s * d - q).norm();
    if (dist < best) {
      best = dist;
      side = Eigen::Vector2d(-d.y(), d.x()).dot(q - a);
    }
  }
  return side;
}

// Pixels reachable from (x,y) through open links.
std::vector<std::uint8_t> flood(const Problem& p, int x, int y) {
  std::vector<std::uint8_t> seen(p.pixel_count(), 0);
  std::queue<int> q;
  q.push(int(p.index(x, y)));
  seen[p.index(x, y)] = 1;
  while (!q.empty()) {
    const int i = q.front();
    q.pop();
    const int px = i % p.width, py = i / p.width;
    const auto go = [&](int j, bool open) {
      if (open && !seen[j]) {
        seen[j] = 1;
        q.push(j);
      }
    };
    go(i + 1, px + 1 < p.width && (p.links[i] & kOpenEast));
    go(i - 1, px > 0 && (p.links[i - 1] & kOpenEast));
    go(i + p.width, py + 1 < p.height && (p.links[i] & kOpenSouth));
    go(i - p.width, py > 0 && (p.links[i - p.width] & kOpenSouth));
  }
  return seen;
}

// A pixel whose value the curves constrain: fixed, or anchored (second order).
bool constrained(const Problem& p, size_t i) {
  return p.fixed[i] || p.anchor_weight[i] > 0;
}

RasterizeOptions sampling(DirichletSampling rule) {
  RasterizeOptions o;
  o.dirichlet = rule;
  return o;
}

// Both sampling rules, one per run of the test case (the first run is the second-order one).
DirichletSampling either_rule() {
  return GENERATE(DirichletSampling::ShortleyWeller, DirichletSampling::NearestClaim);
}

}  // namespace

TEST_CASE("a circle constrains its inside colour inside and its outside colour outside",
          "[rasterize]") {
  const auto c = circle(32, 32, 10, Color(1, 0, 0), Color(0, 0, 1));
  const Problem p = rasterize({c}, 64, 64, sampling(either_rule()));
  const size_t n = p.pixel_count();
  int inside = 0, outside = 0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const size_t i = p.index(x, y);
      if (!constrained(p, i)) continue;
      // Only pixels next to the curve are constrained.
      const double r = std::hypot(x + 0.5 - 32, y + 0.5 - 32);
      CHECK(std::abs(r - 10) < 1.0);
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

TEST_CASE("every fixed pixel lies on the side whose colour it took, for crossing curves",
          "[rasterize]") {
  // The first-order rule: one claim per pixel, so the colour names the curve and its side.
  // Straight segments and circles at random, crossing each other many times (none crosses
  // itself, so "the side of curve k" is well defined everywhere). Each side of each curve has
  // its own colour: (curve index / 10, 1 for left or 0 for right, 0.5).
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> pos(5, 91), rad(5, 30);
  std::vector<DiffusionCurve> curves;
  for (int k = 0; k < 8; ++k) {
    DiffusionCurve c;
    if (k % 2) {
      c = circle(pos(rng), pos(rng), rad(rng), Color(0, 0, 0), Color(0, 0, 0));
    } else {
      const Eigen::Vector2d a(pos(rng), pos(rng)), b(pos(rng), pos(rng));
      c.append(line_cubic(a, b));
    }
    c.left = {{0, Color(k / 10.0f, 1.0f, 0.5f)}};
    c.right = {{0, Color(k / 10.0f, 0.0f, 0.5f)}};
    curves.push_back(c);
  }
  const Problem p = rasterize(curves, 96, 96, sampling(DirichletSampling::NearestClaim));
  const size_t n = p.pixel_count();
  int fixed = 0;
  for (int y = 0; y < 96; ++y)
    for (int x = 0; x < 96; ++x) {
      const size_t i = p.index(x, y);
      if (!p.fixed[i]) continue;
      ++fixed;
      const int k = int(std::lround(p.value[i] * 10));
      const bool left = p.value[n + i] > 0.5f;
      REQUIRE(k >= 0);
      REQUIRE(k < 8);
      const double s = side_of(curves[k], Eigen::Vector2d(x + 0.5, y + 0.5));
      INFO("pixel " << x << "," << y << " curve " << k);
      CHECK((left ? s >= 0 : s <= 0));
    }
  CHECK(fixed > 300);
}

TEST_CASE("a closed curve cuts every link between its inside and its outside", "[rasterize]") {
  // A thin wavy closed wisp (about 1.2 pixels wide in places): flooding from outside never
  // reaches a pixel whose centre is inside.
  DiffusionCurve w;
  w.points = {{10, 30}, {30, 10}, {60, 50}, {90, 30}, {91.2, 31}, {61, 51.2}, {31, 11.2}, {10, 30}};
  w.points.resize(7);
  w.points.back() = w.points.front();
  w.left = {{0, Color(1, 0, 0)}};
  w.right = {{0, Color(0, 0, 1)}};
  const Problem p = rasterize({w}, 100, 60, sampling(either_rule()));
  const auto outside = flood(p, 0, 0);
  for (int y = 0; y < 60; ++y)
    for (int x = 0; x < 100; ++x) {
      const Eigen::Vector2d q(x + 0.5, y + 0.5);
      // The wisp runs root -> tip above and back below: inside is on its right side.
      if (outside[p.index(x, y)])
        CHECK(!(side_of(w, q) < -0.05 && constrained(p, p.index(x, y)) &&
                p.value[p.index(x, y)] == 1.0f));
    }
  // And no inside (red) colour anywhere reachable from the outside through open links.
  const size_t n = p.pixel_count();
  for (size_t i = 0; i < n; ++i)
    if (outside[i] && constrained(p, i)) CHECK(p.value[2 * n + i] == 1.0f);
}

TEST_CASE("a wisp thinner than a pixel leaks no inside colour", "[rasterize]") {
  // Lenses 0.3 pixels thick, root -> tip along one side and back along the other, so that
  // their inside is on the left of travel. A pixel may take the inside colour only if its
  // centre really is inside; everywhere else both sides show the outside colour.
  const auto lens = [](std::vector<Eigen::Vector2d> top, std::vector<Eigen::Vector2d> bottom) {
    DiffusionCurve w;
    w.points = {top[0], top[1], top[2], top[3], bottom[2], bottom[1], top[0]};
    w.left = {{0, Color(0, 0, 1)}};   // inside: blue
    w.right = {{0, Color(1, 0, 0)}};  // outside: red
    return w;
  };
  const RasterizeOptions options = sampling(either_rule());
  SECTION("between two rows of pixel centres: no centre inside, two crossings per link") {
    const DiffusionCurve w = lens({{5, 20.75}, {20, 20.6}, {40, 20.6}, {55, 20.75}},
                                  {{5, 20.75}, {20, 20.9}, {40, 20.9}, {55, 20.75}});
    const Problem p = rasterize({w}, 60, 40, options);
    const size_t n = p.pixel_count();
    int above = 0, below = 0;
    for (size_t i = 0; i < n; ++i)
      if (constrained(p, i)) {
        CHECK(p.value[2 * n + i] == 0.0f);  // never the inside's blue
        (i / 60 == 20 ? above : below)++;
      }
    CHECK(above >= 45);  // the outside colour on both sides all along
    CHECK(below >= 45);
  }
  SECTION("slanted: the inside colour only at centres that are inside") {
    const DiffusionCurve w = lens({{5, 19.85}, {20, 9.85}, {40, 29.85}, {55, 20}},
                                  {{5, 19.85}, {20, 10.15}, {40, 30.15}, {55, 20}});
    const Problem p = rasterize({w}, 60, 40, options);
    const size_t n = p.pixel_count();
    // Inside test by the winding number of the finely flattened outline.
    const auto poly = flatten(w, 1e-4);
    const auto inside = [&](const Eigen::Vector2d& q) {
      int wn = 0;
      for (size_t k = 1; k < poly.size(); ++k) {
        const Eigen::Vector2d a = poly[k - 1].p, b = poly[k].p;
        const double cr = (b.x() - a.x()) * (q.y() - a.y()) - (q.x() - a.x()) * (b.y() - a.y());
        if (a.y() <= q.y() && b.y() > q.y() && cr > 0) ++wn;
        if (a.y() > q.y() && b.y() <= q.y() && cr < 0) --wn;
      }
      return wn != 0;
    };
    int blue = 0, red = 0;
    for (size_t i = 0; i < n; ++i)
      if (constrained(p, i)) {
        const bool is_blue = p.value[2 * n + i] == 1.0f;
        CHECK(is_blue == inside(Eigen::Vector2d(i % 60 + 0.5, i / 60 + 0.5)));
        (is_blue ? blue : red)++;
      }
    CHECK(red > 60);
  }
}

TEST_CASE("Neumann sides constrain nothing but still cut", "[rasterize]") {
  auto c = circle(32, 32, 10, Color(1, 0, 0), Color(0, 0, 1));
  c.right_boundary = Boundary::Neumann;
  RasterizeOptions options = sampling(either_rule());
  options.neumann = GENERATE(NeumannSides::Transparent, NeumannSides::Opaque);
  const Problem p = rasterize({c}, 64, 64, options);
  int inside = 0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      if (constrained(p, p.index(x, y))) {
        CHECK(std::hypot(x + 0.5 - 32, y + 0.5 - 32) < 10);
        ++inside;
      }
  CHECK(inside > 40);  // the ring of pixels just inside
  const auto outside = flood(p, 0, 0);
  CHECK(!outside[p.index(32, 32)]);
  for (size_t i = 0; i < p.pixel_count(); ++i) CHECK(!(outside[i] && constrained(p, i)));
}

TEST_CASE("a Dirichlet claim at a pixel centre behind a Neumann one there stays finite",
          "[rasterize]") {
  // Two curves through the centre of pixel (10, 10): an insulating one (Neumann on both sides,
  // first in drawing order, so it wins the ties) along the row, a coloured one along the column.
  // The Neumann claims fix nothing, so the pixel is anchored by the coloured curve's claims at
  // distance 0 (ladybug at 1024x1024 met this and its problem held NaN).
  DiffusionCurve insulating;
  insulating.points = {{0, 10.5}, {7, 10.5}, {14, 10.5}, {21, 10.5}};
  insulating.left = insulating.right = {{0, Color(0, 0, 0)}};
  insulating.left_boundary = insulating.right_boundary = Boundary::Neumann;
  DiffusionCurve coloured;
  coloured.points = {{10.5, 0}, {10.5, 7}, {10.5, 14}, {10.5, 21}};
  coloured.left = coloured.right = {{0, Color(1, 0.5, 0.25)}};
  // Second order (the first-order rule leaves a pixel whose nearest claim is Neumann free).
  const Problem p = rasterize({insulating, coloured}, 21, 21);
  for (float v : p.value) REQUIRE(std::isfinite(v));
  const size_t centre = p.index(10, 10);
  CHECK(constrained(p, centre));
  CHECK(p.value[centre] == Approx(1));  // planes of W*H per channel
  CHECK(p.value[2 * p.pixel_count() + centre] == Approx(0.25));
}

TEST_CASE("an opaque Neumann side hides the Dirichlet colour behind it on the same link",
          "[rasterize]") {
  // A lens 0.15-0.3 pixels thick between two rows of pixel centres, black inside, Neumann
  // outside: every link across it meets the outer side first, then the inner side facing the
  // same pixel (crane's thin feathers and legs).
  DiffusionCurve w;
  w.points = {{5, 20.75}, {20, 20.6}, {40, 20.6}, {55, 20.75}, {40, 20.9}, {20, 20.9}, {5, 20.75}};
  w.left = {{0, Color(0, 0, 0)}};  // inside
  w.right_boundary = Boundary::Neumann;
  RasterizeOptions options = sampling(either_rule());
  SECTION("opaque (the default, small-usvg's): the outer side is nearest, so no pixel is black") {
    const Problem p = rasterize({w}, 60, 40, options);
    for (size_t i = 0; i < p.pixel_count(); ++i) CHECK(!constrained(p, i));
    CHECK(!(p.links[p.index(30, 20)] & kOpenSouth));  // and the lens still cuts
  }
  SECTION("transparent: the inner side's black reaches the pixels on both sides") {
    options.neumann = NeumannSides::Transparent;
    const Problem p = rasterize({w}, 60, 40, options);
    int black = 0;
    for (size_t i = 0; i < p.pixel_count(); ++i) black += constrained(p, i);
    CHECK(black >= 90);
  }
}

TEST_CASE("only the active parameter intervals constrain", "[rasterize]") {
  auto c = circle(32, 32, 10, Color(1, 0, 0), Color(0, 0, 1));
  c.active = {{0.0, 0.5}};  // the lower half of the circle (angles 0..pi, y down)
  const Problem p = rasterize({c}, 64, 64, sampling(either_rule()));
  int upper = 0, lower = 0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      if (constrained(p, p.index(x, y))) (y + 0.5 > 32 ? lower : upper)++;
  CHECK(lower > 30);
  CHECK(upper <= 2);  // at most the two end pixels of the half circle
  // The open upper half lets the inside and outside connect.
  CHECK(flood(p, 0, 0)[p.index(32, 32)]);
}

TEST_CASE("a gradient curve imposes its colour jump, not its colours", "[rasterize]") {
  // Frame of fixed colour 0.2 (a Dirichlet rectangle near the border); inside it a gradient
  // circle whose right-minus-left jump is -0.3 going outwards: the inside must come out at
  // 0.2 + 0.3 = 0.5 exactly, although no pixel is fixed to 0.5 anywhere.
  DiffusionCurve frame;
  frame.points = {{2, 2},   {30, 2}, {60, 2}, {62, 2}, {62, 30}, {62, 60}, {62, 62},
                  {30, 62}, {4, 62}, {2, 62}, {2, 30}, {2, 4},   {2, 2}};
  frame.left = {{0, Color(0.2f, 0.2f, 0.2f)}};
  frame.right = frame.left;
  auto g = circle(32, 32, 12, Color(0.5f, 0.5f, 0.5f), Color(0.2f, 0.2f, 0.2f));
  g.gradient_only = true;
  const Problem p = rasterize({frame, g}, 64, 64);
  CHECK(!p.rhs.empty());
  CHECK(!constrained(p, p.index(32, 32)));
  SolverOptions opt;
  opt.tolerance = 1e-8;
  const Solution s = solve_multigrid(p, opt);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const double r = std::hypot(x + 0.5 - 32, y + 0.5 - 32);
      if (r < 11) CHECK(s.planes[p.index(x, y)] == Approx(0.5f).margin(1e-4));
      if (r > 13 && x > 3 && y > 3 && x < 61 && y < 61)
        CHECK(s.planes[p.index(x, y)] == Approx(0.2f).margin(1e-4));
    }
}

namespace {

// A straight curve from a to b (a cubic with its control points on the line, so that flattening
// is exact and the parameter runs uniformly).
DiffusionCurve segment(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  DiffusionCurve c;
  c.points = {a, a + (b - a) / 3, a + 2 * (b - a) / 3, b};
  return c;
}

}  // namespace

TEST_CASE("anchors weigh the inverse distance to the nearest crossing on each link",
          "[rasterize]") {
  // A closed triangle of straight pieces whose inside colour is the grey t (the path parameter)
  // and whose outside is 0.9. The anchors are recomputed by intersecting each pixel's four links
  // with the exact triangle.
  const std::vector<Eigen::Vector2d> v = {{5.37, 6.81}, {41.23, 14.52}, {13.91, 37.16}};
  DiffusionCurve tri;
  tri.points = {v[0]};
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector2d a = v[k], b = v[(k + 1) % 3];
    tri.points.insert(tri.points.end(), {a + (b - a) / 3, a + 2 * (b - a) / 3, b});
  }
  tri.left = {{0, Color(0, 0, 0)}, {1, Color(1, 1, 1)}};
  tri.right = {{0, Color(0.9f, 0.9f, 0.9f)}};
  const Problem p = rasterize({tri}, 48, 48);
  const size_t n = p.pixel_count();
  int anchored = 0, mixed = 0;
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 48; ++x) {
      const Eigen::Vector2d c(x + 0.5, y + 0.5);
      double weight = 0, sum = 0, nearest = 1;
      int claims = 0;
      for (const Eigen::Vector2d& d : {Eigen::Vector2d(1, 0), Eigen::Vector2d(-1, 0),
                                       Eigen::Vector2d(0, 1), Eigen::Vector2d(0, -1)}) {
        // The nearest crossing of the link c -> c + d with an edge of the triangle.
        double theta = 2, colour = 0;
        for (int k = 0; k < 3; ++k) {
          const Eigen::Vector2d a = v[k], e = v[(k + 1) % 3] - a;
          const double den = d.x() * e.y() - d.y() * e.x();
          if (den == 0) continue;
          const Eigen::Vector2d ac = a - c;
          const double s = (ac.x() * e.y() - ac.y() * e.x()) / den;  // along the link
          const double u = (ac.x() * d.y() - ac.y() * d.x()) / den;  // along the edge
          if (s < 0 || s >= 1 || u < 0 || u > 1 || s >= theta) continue;
          theta = s;
          const bool left = Eigen::Vector2d(-e.y(), e.x()).dot(c - a) > 0;
          colour = left ? (k + u) / 3 : 0.9;
        }
        if (theta > 1) continue;
        ++claims;
        nearest = std::min(nearest, theta);
        weight += 1 / theta;
        sum += colour / theta;
      }
      const size_t i = p.index(x, y);
      INFO("pixel " << x << "," << y);
      REQUIRE(nearest >= kMinAnchorDistance);  // no pixel is fixed in this layout
      CHECK(!p.fixed[i]);
      if (claims == 0) {
        CHECK(p.anchor_weight[i] == 0.0f);
        continue;
      }
      ++anchored;
      mixed += claims > 1;
      CHECK(p.anchor_weight[i] == Approx(weight).epsilon(1e-5));
      for (int ch = 0; ch < 3; ++ch)
        CHECK(p.value[ch * n + i] == Approx(sum / weight).margin(1e-5));
    }
  CHECK(anchored > 150);
  CHECK(mixed > 20);
}

TEST_CASE("a straight edge at a fractional position gives the exact linear profile",
          "[rasterize]") {
  // Two parallel lines across the image at x = 10.3 and 37.8 (or the same in y), colour and blur
  // 0.1 / 1 on the first and 0.7 / 3 on the second: between them the exact solution is linear,
  // and the second-order boundary reproduces it at every pixel, including those next to the
  // lines. The first-order rule moves the boundary to pixel centres, off by up to 0.01 here.
  const bool across_y = GENERATE(false, true);
  const double a = 10.3, b = 37.8;
  const auto line = [&](double at, float colour, float blur) {
    DiffusionCurve c = segment({at, -1}, {at, 17});
    if (across_y)
      for (Eigen::Vector2d& q : c.points) q = Eigen::Vector2d(q.y(), q.x());
    c.left = c.right = {{0, Color(colour, colour, colour)}};
    c.blur = {{0, blur}};
    return c;
  };
  const int w = across_y ? 16 : 48, h = across_y ? 48 : 16;
  for (const DirichletSampling rule :
       {DirichletSampling::ShortleyWeller, DirichletSampling::NearestClaim}) {
    RasterizeOptions options = sampling(rule);
    options.blur_channel = true;
    const Problem p = rasterize({line(a, 0.1f, 1), line(b, 0.7f, 3)}, w, h, options);
    SolverOptions tight;
    tight.tolerance = 1e-10;
    const Solution s = solve_multigrid(p, tight);
    const ReferenceResult exact = solve_reference(p, ReferenceMethod::SimplicialLDLT);
    const size_t n = p.pixel_count();
    double error = 0, reference_error = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const double at = (across_y ? y : x) + 0.5;
        if (at < a || at > b) continue;
        const double f = (at - a) / (b - a);
        const size_t i = p.index(x, y);
        for (int c = 0; c < 4; ++c) {
          const double want = c < 3 ? 0.1 + 0.6 * f : 1 + 2 * f;
          error = std::max(error, std::abs(s.planes[c * n + i] - want));
          reference_error = std::max(reference_error, std::abs(exact.planes[c * n + i] - want));
        }
      }
    INFO("across y " << across_y << ", first order " << (rule == DirichletSampling::NearestClaim)
                     << ": error " << error << ", reference " << reference_error);
    if (rule == DirichletSampling::ShortleyWeller) {
      CHECK(error <= 2e-6);
      CHECK(reference_error <= 2e-6);
    } else {
      CHECK(error >= 5e-3);
    }
  }
}

TEST_CASE("the second-order boundary converges at second order between two circles",
          "[rasterize]") {
  // Concentric circles r1 < r2 with colours c1, c2: between them u = c1 + (c2 - c1) ln(r/r1) /
  // ln(r2/r1). The largest error at pixel centres between the circles must fall about 4x per
  // doubling of the resolution; the first-order rule's falls about 2x.
  const double c1 = 0.2, c2 = 0.8;
  const auto max_error = [&](int size, DirichletSampling rule) {
    const Eigen::Vector2d centre = size * Eigen::Vector2d(0.5013, 0.4987);
    const double r1 = 0.2 * size, r2 = 0.43 * size;
    const Color k1(c1, c1, c1), k2(c2, c2, c2);
    RasterizeOptions options = sampling(rule);
    options.flatten_tolerance = 1e-4;  // the geometry is the same circle at every size
    const Problem p = rasterize({circle(centre.x(), centre.y(), r1, k1, k1, 16),
                                 circle(centre.x(), centre.y(), r2, k2, k2, 16)},
                                size, size, options);
    const ReferenceResult u = solve_reference(p, ReferenceMethod::SimplicialLDLT);
    double err = 0;
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        const double r = (Eigen::Vector2d(x + 0.5, y + 0.5) - centre).norm();
        if (r <= r1 || r >= r2) continue;
        const double want = c1 + (c2 - c1) * std::log(r / r1) / std::log(r2 / r1);
        err = std::max(err, std::abs(u.planes[p.index(x, y)] - want));
      }
    return err;
  };
  for (const DirichletSampling rule :
       {DirichletSampling::ShortleyWeller, DirichletSampling::NearestClaim}) {
    const double e64 = max_error(64, rule), e128 = max_error(128, rule),
                 e256 = max_error(256, rule);
    INFO("first order " << (rule == DirichletSampling::NearestClaim) << ": errors " << e64 << ", "
                        << e128 << ", " << e256);
    if (rule == DirichletSampling::ShortleyWeller) {
      CHECK(e64 / e128 >= 3);
      CHECK(e128 / e256 >= 3);
    } else {
      CHECK(e64 / e128 <= 2.5);
      CHECK(e128 / e256 <= 2.5);
    }
  }
}

TEST_CASE("a window's problem is the whole image's inside it, with its own edges as the border",
          "[rasterize]") {
  // Circles at fractional places, one of them crossing the window's edge, another outside it.
  const Color red(1, 0, 0), blue(0, 0, 1);
  const std::vector<DiffusionCurve> curves = {circle(40.3, 37.7, 15.2, red, blue),
                                              circle(61.5, 20.25, 9.9, blue, red),
                                              circle(9.6, 70.1, 6.3, red, red)};
  const Problem whole = rasterize(curves, 96, 96);
  const PixelWindow window{20, 16, 48, 40};
  const Problem part = rasterize(curves, window);
  REQUIRE(part.width == window.width);
  REQUIRE(part.height == window.height);
  const size_t n = whole.pixel_count(), m = part.pixel_count();
  int anchored = 0;
  for (int y = 0; y < part.height; ++y)
    for (int x = 0; x < part.width; ++x) {
      const size_t i = part.index(x, y), j = whole.index(window.x + x, window.y + y);
      INFO("window pixel " << x << "," << y);
      REQUIRE(part.fixed[i] == whole.fixed[j]);
      REQUIRE(part.anchor_weight[i] == whole.anchor_weight[j]);
      for (int c = 0; c < 3; ++c) REQUIRE(part.value[c * m + i] == whole.value[c * n + j]);
      // Links leaving the window do not exist; the others are the whole image's.
      const std::uint8_t border = std::uint8_t((x + 1 < part.width ? kOpenEast : 0) |
                                               (y + 1 < part.height ? kOpenSouth : 0));
      REQUIRE(part.links[i] == (whole.links[j] & border));
      anchored += part.anchor_weight[i] > 0;
    }
  CHECK(anchored > 50);  // the circles do cross the window
}

TEST_CASE("the curves' window holds every curve with its margin, on the lattice, in the image",
          "[rasterize]") {
  CHECK(curves_window({}, 100, 100, 8, 32) == PixelWindow{});
  const Color c(1, 1, 1);
  // A circle's control points span [x - r, x + r] x [y - r, y + r]; 8 more each side, then out
  // to multiples of 32: [32.5, 68.5] x [22, 58] -> [32, 96) x [0, 64).
  CHECK(curves_window({circle(50.5, 40, 10, c, c)}, 200, 150, 8, 32) == PixelWindow{32, 0, 64, 64});
  CHECK(curves_window({circle(120, 100, 10, c, c)}, 200, 150, 8, 32) ==
        PixelWindow{96, 64, 64, 64});
  // Reaching outside the image: clipped to it.
  CHECK(curves_window({circle(190, -20, 30, c, c)}, 200, 150, 8, 32) ==
        PixelWindow{128, 0, 72, 32});
  CHECK(curves_window({circle(300, 300, 10, c, c)}, 200, 150, 8, 32) == PixelWindow{});
}
