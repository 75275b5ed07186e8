// The hair base: traced from its field as closed paths with the base on their left (holes turn
// the other way), exact to the field; in the arrangement it lies behind every wisp and in front
// of the head it is drawn on, is hair (in the mask) where it shows, and its boundary is visible
// only there; its curves carry its colour on the base's side alone.
#include <catch2/catch.hpp>
#include <cmath>

#include "diffusion/bezier.hpp"
#include "tests/vector/scenes.hpp"
#include "vector/arrangement.hpp"
#include "vector/hair_base.hpp"
#include "vector/polygon.hpp"
#include "vector/stroke_fit.hpp"

using namespace wisp;
using Eigen::Vector2d;

namespace {

double mask_area(const vector::HairMask& m) {
  double a = 0;
  for (const auto& p : m.polygons) {
    a += std::abs(vector::signed_area(p.outer));
    for (const auto& h : p.holes) a -= std::abs(vector::signed_area(h));
  }
  return a;
}

// A disc of radius r around c, at constant depth, with a hole of radius `hole` (0: none).
vector::HairBase disc(Vector2d c, double r, double depth, double hole = 0) {
  const auto field = [=](const Vector2d& p) {
    const double d = (p - c).norm();
    return hole > 0 ? std::min(r - d, d - hole) : r - d;
  };
  return vector::trace_hair_base(
      field, [depth](const Vector2d&) { return depth; },
      Eigen::AlignedBox2d(c - Vector2d(r, r), c + Vector2d(r, r)));
}

vector::Occluder square(double x0, double y0, double x1, double y1, double depth) {
  vector::Occluder o;
  o.ring = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
  o.depth = [depth](const Vector2d&) { return depth; };
  return o;
}

vector::WispArrangement arrange(const std::vector<vector::Wisp>& wisps,
                                std::vector<vector::Occluder> occluders, vector::HairBase base) {
  vector::ArrangementOptions o;
  o.view = vector::image_rect(512, 512);
  o.front_regions = true;
  o.occluders = std::move(occluders);
  o.base = std::move(base);
  return vector::build_arrangement(wisps, o);
}

// A straight wisp 20 px wide at the given depth (constant profile, square ends).
vector::Wisp band(Vector2d a, Vector2d b, double depth) {
  vector::WispStyle s;
  s.width = 0.05 * depth / 2;
  s.profile = vector::WidthProfile::constant();
  s.root_taper = 0;
  auto w = vector::build_wisp(test::straight(0, a, b, depth, depth, 8), 800, s);
  REQUIRE(w);
  return *w;
}

}  // namespace

TEST_CASE("the hair base is traced from its field: closed paths, base on their left, exact",
          "[vector][base]") {
  const vector::HairBase one = disc({200, 200}, 60, 1);
  REQUIRE(one.paths.size() == 1);
  REQUIRE(one.rings.size() == 1);
  const auto& path = one.paths[0];
  CHECK(path.closed());
  // Counter-clockwise in (x, y): the base on the left; the area of the disc.
  CHECK(vector::signed_area(one.rings[0]) == Approx(M_PI * 60 * 60).epsilon(3e-3));
  // Every ring vertex lies on the circle (fit 0.1 px, flattening 0.05 px).
  double worst = 0;
  for (const Vector2d& p : one.rings[0])
    worst = std::max(worst, std::abs((p - Vector2d(200, 200)).norm() - 60));
  CHECK(worst < 0.16);
  // Ring parameters run along the path.
  const auto& s = one.ring_s[0];
  REQUIRE(s.size() == one.rings[0].size());
  for (size_t i = 1; i < s.size(); ++i) CHECK(s[i] > s[i - 1]);
  for (size_t i = 0; i < s.size(); i += 7)
    CHECK((diffusion::eval(path, s[i]) - one.rings[0][i]).norm() < 1e-6);

  // An annulus: the outer ring counter-clockwise, the hole clockwise.
  const vector::HairBase ring = disc({200, 200}, 60, 1, 25);
  REQUIRE(ring.rings.size() == 2);
  double total = 0;
  for (const auto& r : ring.rings) total += vector::signed_area(r);
  CHECK(total == Approx(M_PI * (60 * 60 - 25 * 25)).epsilon(2e-3));
  // A region running past the box is cut on the padded box: closed, just outside it.
  const vector::HairBase cut = vector::trace_hair_base(
      [](const Vector2d& p) { return 100 - p.x(); }, [](const Vector2d&) { return 1.0; },
      Eigen::AlignedBox2d(Vector2d(0, 0), Vector2d(200, 200)));
  REQUIRE(cut.rings.size() == 1);
  const Eigen::AlignedBox2d box = [&] {
    Eigen::AlignedBox2d b;
    for (const Vector2d& p : cut.rings[0]) b.extend(p);
    return b;
  }();
  CHECK(box.max().x() == Approx(100).margin(1e-3));
  CHECK(box.min().x() < 0);
  CHECK(box.min().y() < 0);
  CHECK(box.max().y() > 200);
}

TEST_CASE("the hair base lies behind every wisp and in front of its head, and is hair",
          "[vector][base]") {
  // A base disc on a head (a square occluder) and a wisp across both, nearer the eye.
  const vector::Wisp w = band({100, 200}, {400, 200}, 2.0);
  const double wisp_area = 300 * 20;
  const double disc_area = M_PI * 60 * 60;
  SECTION("alone") {
    const auto arr = arrange({}, {}, disc({250, 200}, 60, 3.0));
    CHECK(mask_area(arr.mask) == Approx(disc_area).epsilon(2e-3));
    CHECK(mask_area(arr.base_region) == Approx(disc_area).epsilon(2e-3));
    REQUIRE(arr.base_visible.size() == 1);
    REQUIRE(arr.base_visible[0].size() == 1);
    CHECK(arr.base_visible[0][0].first == Approx(0).margin(1e-9));
    CHECK(arr.base_visible[0][0].second == Approx(1).margin(1e-9));
    CHECK(!arr.silhouette.empty());
  }
  SECTION("under a wisp: even a wisp farther than the base is in front of it") {
    for (double base_depth : {3.0, 1.0}) {
      const auto arr = arrange({w}, {}, disc({250, 200}, 60, base_depth));
      // The wisp crosses the disc through its centre: the base shows around it.
      const double overlap = 120 * 20 - 2 * (60 - std::sqrt(60 * 60 - 10 * 10)) * 20 / 3;
      CHECK(mask_area(arr.base_region) == Approx(disc_area - overlap).epsilon(0.01));
      CHECK(mask_area(arr.mask) == Approx(disc_area + wisp_area - overlap).epsilon(0.01));
      CHECK(mask_area(arr.front_regions[0]) == Approx(wisp_area).epsilon(0.01));
      // The wisp's outline is visible all along; the base's boundary wherever it shows.
      double seen = 0;
      for (const auto& [a, b] : arr.visible[0]) seen += b - a;
      CHECK(seen == Approx(1).margin(1e-6));
      // The wisp's edges over the base are occlusion lines, not silhouettes.
      CHECK(!arr.occlusion.empty());
    }
  }
  SECTION("on a head: the head hides the wisp passing behind it, never the base") {
    // The head's square is nearer than the far wisp (depth 5) but farther than the base.
    const vector::Wisp far = band({100, 200}, {400, 200}, 5.0);
    const auto arr = arrange({far}, {square(150, 100, 350, 300, 4.0)}, disc({250, 200}, 60, 3.9));
    CHECK(mask_area(arr.base_region) == Approx(disc_area).epsilon(2e-3));
    // The wisp shows only outside the head: 2 x 50 px of its length.
    CHECK(mask_area(arr.front_regions[0]) == Approx(2 * 50 * 20).epsilon(0.01));
    // The base's boundary is visible all round.
    double seen = 0;
    for (const auto& [a, b] : arr.base_visible[0]) seen += b - a;
    CHECK(seen == Approx(1).margin(1e-6));
  }
  SECTION("behind the neck: an occluder nearer than the base hides it") {
    const auto arr = arrange({}, {square(250, 100, 400, 300, 2.0)}, disc({250, 200}, 60, 3.0));
    CHECK(mask_area(arr.base_region) == Approx(disc_area / 2).epsilon(3e-3));
    double seen = 0;
    for (const auto& [a, b] : arr.base_visible[0]) seen += b - a;
    CHECK(seen == Approx(0.5).margin(0.01));
  }
}

TEST_CASE("the hair base's curves carry its colour on its side only, where it shows",
          "[vector][base]") {
  const vector::HairBase base = disc({250, 200}, 60, 3.0, 20);
  const auto arr = arrange({}, {square(250, 100, 400, 300, 2.0)}, base);
  const Eigen::Vector3f colour(0.3f, 0.2f, 0.1f);
  const auto curves = vector::base_curves(base, arr.base_visible, colour);
  REQUIRE(curves.size() == 2);
  for (size_t i = 0; i < curves.size(); ++i) {
    CHECK(curves[i].points == base.paths[i].points);
    CHECK(curves[i].left_boundary == diffusion::Boundary::Dirichlet);
    CHECK(curves[i].right_boundary == diffusion::Boundary::Neumann);
    CHECK(diffusion::color_at(curves[i].left, 0.5) == colour);
    CHECK(curves[i].active == arr.base_visible[i]);
  }
  // The base's colour: `tone` of the way from the shadow to the hair colour.
  vector::HairStyle style;
  style.base.tone = 0.25;
  CHECK((vector::base_color(style) - (style.shadow + 0.25f * (style.hair - style.shadow))).norm() <
        1e-6);
}
