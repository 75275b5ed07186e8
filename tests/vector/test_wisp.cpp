// Wisp construction: centre spline, width profile, perspective, width limit, outline layout, and
// what happens to bad input.
#include <catch2/catch.hpp>
#include <cmath>

#include "tests/vector/scenes.hpp"
#include "vector/catmull_rom.hpp"
#include "vector/wisp.hpp"

using namespace wisp;
using diffusion::derivative;
using diffusion::eval;
using Eigen::Vector2d;
using Eigen::Vector3d;

namespace {

double cross(const Vector2d& a, const Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Centripetal Catmull-Rom by the Barry-Goldman pyramid, evaluated at knot parameter t in
// [t1, t2] (independent of the Bezier conversion under test).
Vector2d barry_goldman(const Vector2d& p0, const Vector2d& p1, const Vector2d& p2,
                       const Vector2d& p3, double t) {
  const double t0 = 0, t1 = t0 + std::sqrt((p1 - p0).norm()), t2 = t1 + std::sqrt((p2 - p1).norm()),
               t3 = t2 + std::sqrt((p3 - p2).norm());
  auto lerp = [](const Vector2d& a, const Vector2d& b, double ta, double tb, double x) -> Vector2d {
    return (tb - x) / (tb - ta) * a + (x - ta) / (tb - ta) * b;
  };
  const Vector2d a1 = lerp(p0, p1, t0, t1, t1 + t * (t2 - t1)),
                 a2 = lerp(p1, p2, t1, t2, t1 + t * (t2 - t1)),
                 a3 = lerp(p2, p3, t2, t3, t1 + t * (t2 - t1));
  const double x = t1 + t * (t2 - t1);
  const Vector2d b1 = lerp(a1, a2, t0, t2, x), b2 = lerp(a2, a3, t1, t3, x);
  return lerp(b1, b2, t1, t2, x);
}

double signed_area(const std::vector<vector::OutlineVertex>& poly) {
  double a = 0;
  for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++)
    a += cross(poly[j].p, poly[i].p);
  return a / 2;
}

vector::WispStyle wide() {
  vector::WispStyle s;
  s.width = 0.05;
  s.root_taper = 0;  // the profile alone; the root taper has its own test
  return s;
}

}  // namespace

TEST_CASE("centre spline is the centripetal Catmull-Rom spline through the samples",
          "[vector][wisp]") {
  const std::vector<Vector2d> p = {{10, 10}, {40, 12}, {45, 60}, {90, 70}, {91, 71}, {150, 20}};
  const diffusion::BezierPath path = vector::catmull_rom_path(p);
  const int spans = path.piece_count();
  REQUIRE(spans == int(p.size()) - 1);
  for (int i = 0; i < spans; ++i) {
    const diffusion::Cubic span = path.piece(i);
    CHECK(span[0] == p[i]);
    CHECK(span[3] == p[i + 1]);
    if (i == 0 || i + 2 >= int(p.size())) continue;  // interior spans: compare with the pyramid
    for (double u : {0.1, 0.37, 0.5, 0.81})
      CHECK((eval(span, u) - barry_goldman(p[i - 1], p[i], p[i + 1], p[i + 2], u)).norm() < 1e-9);
  }
  // G1 joints: the tangent direction does not jump between spans.
  for (int i = 0; i + 1 < spans; ++i) {
    const Vector2d a = derivative(path.piece(i), 1).normalized();
    const Vector2d b = derivative(path.piece(i + 1), 0).normalized();
    CHECK((a - b).norm() < 1e-9);
  }
  // Two points: one straight span.
  const diffusion::Cubic line = vector::catmull_rom_path({{0, 0}, {9, 3}}).piece(0);
  CHECK(std::abs(cross(line[1] - line[0], Vector2d(9, 3))) < 1e-9);
  CHECK(std::abs(cross(line[2] - line[0], Vector2d(9, 3))) < 1e-9);
  CHECK(vector::catmull_rom_path({{1, 1}}).piece_count() == 0);
}

TEST_CASE("centre spline carries depth, tangent and strand parameter per control point",
          "[vector][wisp]") {
  const auto s = test::straight(3, {50, 50}, {150, 80}, 2.0, 3.0, 5);
  const auto w = vector::build_wisp(s, 800, wide());
  REQUIRE(w);
  const auto& c = w->centre;
  REQUIRE(c.points.size() == 13);
  REQUIRE(c.depth.size() == 13);
  for (int i = 0; i < 13; ++i) {
    CHECK(c.depth[i] == Approx(2.0 + i / 12.0).epsilon(1e-12));  // linear along the strand
    CHECK(c.strand_u[i] == Approx(i / 12.0).margin(1e-12));
    CHECK(c.tangent[i].norm() == Approx(1));
  }
  CHECK(w->strand == 3);
}

TEST_CASE("width profiles: Faraj's taper and Shin's sine", "[vector][wisp]") {
  const auto faraj = vector::WidthProfile::faraj_taper();
  CHECK(faraj.at(0) == 1);
  CHECK(faraj.at(1) == 0);
  CHECK(faraj.at(0.25) == Approx(0.75));
  const auto shin = vector::WidthProfile::shin();
  CHECK(shin.at(0) == Approx(0.5));
  CHECK(shin.at(0.4) == Approx(1));
  CHECK(shin.at(1) == Approx(0).margin(1e-12));
  vector::WidthProfile bad;
  bad.controls = {{0.5, 1}, {0.2, 1}};
  CHECK_THROWS_AS(vector::validate(bad), std::invalid_argument);
}

TEST_CASE("wisp width follows perspective, the profile and the root taper", "[vector][wisp]") {
  // A straight strand at constant depth 2: half-width = 0.5 * 0.05 * 800 / 2 = 10 px at the root.
  const auto s = test::straight(0, {50, 100}, {250, 100}, 2.0, 2.0, 6);
  for (auto profile : {vector::WidthProfile::faraj_taper(), vector::WidthProfile::shin()})
    for (double taper : {0.0, 0.3}) {
      auto style = wide();
      style.profile = profile;
      style.root_taper = taper;
      const auto w = vector::build_wisp(s, 800, style);
      REQUIRE(w);
      for (const auto& sec : w->sections) {
        const double u = (sec.centre.x() - 50) / 200;
        const double grow = u < taper ? std::sin(M_PI / 2 * u / taper) : 1.0;
        // The width table's interpolation follows the sine's bend within a few tenths of a pixel;
        // elsewhere each side's cubic is within the fit tolerance of the exact offset.
        const double margin = u < taper + 0.05 ? 0.2 : 2 * style.fit_tolerance_px;
        CHECK((sec.left - sec.right).norm() == Approx(20 * profile.at(u) * grow).margin(margin));
      }
    }
  // Twice as far, half as wide.
  const auto far =
      vector::build_wisp(test::straight(0, {50, 100}, {250, 100}, 4.0, 4.0, 6), 800, wide());
  CHECK((far->sections[0].left - far->sections[0].right).norm() == Approx(10).margin(1e-9));
}

TEST_CASE("outline is closed root to tip to root with the interior at winding +1",
          "[vector][wisp]") {
  const auto s = test::straight(0, {50, 100}, {250, 140}, 2.0, 3.0, 6);
  const auto w = vector::build_wisp(s, 800, wide());
  REQUIRE(w);
  const auto& o = w->outline;
  REQUIRE(o.side.size() == size_t(o.piece_count()));
  CHECK(o.closed());
  // Left side root to tip, then right side back, then the root cap (Faraj's taper: no tip cap).
  CHECK(o.side.front() == vector::Side::Left);
  CHECK(o.side.back() == vector::Side::Root);
  CHECK(std::count(o.side.begin(), o.side.end(), vector::Side::Tip) == 0);
  CHECK(o.t.front() == 0);
  const auto lefts = std::count(o.side.begin(), o.side.end(), vector::Side::Left);
  CHECK(o.t[3 * lefts] == Approx(1));  // the left side ends at the tip
  // Depth per control point is the centre's depth at the point's parameter.
  for (size_t i = 0; i < o.points.size(); ++i)
    CHECK(o.depth[i] == Approx(2.0 + o.t[i]).epsilon(1e-9));
  const auto poly = vector::outline_polygon(*w);
  CHECK(signed_area(poly) > 0);
  // Side::Left is the on-screen left of travel (y down): towards (d.y, -d.x).
  const Vector2d d = Vector2d(200, 40).normalized();
  CHECK((w->sections[0].left - w->sections[0].centre).dot(Vector2d(d.y(), -d.x())) > 0);
}

TEST_CASE("the polygon of a run of a band's cells is closed by its two sections",
          "[vector][wisp]") {
  const auto w =
      vector::build_wisp(test::straight(0, {50, 100}, {250, 140}, 2.0, 3.0, 6), 800, wide());
  REQUIRE(w);
  REQUIRE(w->sections.size() >= 4);
  const auto& sec = w->sections;
  const auto poly = vector::outline_polygon(*w, 1, 3);
  REQUIRE(poly.size() == 6);
  const Vector2d expected[6] = {sec[1].left,  sec[2].left,  sec[3].left,
                                sec[3].right, sec[2].right, sec[1].right};
  const vector::Side sides[6] = {vector::Side::Left,  vector::Side::Left,  vector::Side::Tip,
                                 vector::Side::Right, vector::Side::Right, vector::Side::Root};
  for (int i = 0; i < 6; ++i) {
    CHECK(poly[i].p == expected[i]);
    CHECK(poly[i].side == sides[i]);
  }
  CHECK(signed_area(poly) > 0);  // turns the way the whole outline does
  // The whole range is the whole outline.
  const auto all = vector::outline_polygon(*w, 0, int(sec.size()) - 1);
  const auto whole = vector::outline_polygon(*w);
  REQUIRE(all.size() == whole.size());
  for (size_t i = 0; i < all.size(); ++i) CHECK(all[i].p == whole[i].p);
}

TEST_CASE("a tapered root starts at a point: no root cap, no cut end", "[vector][wisp]") {
  const auto s = test::straight(0, {50, 100}, {250, 140}, 2.0, 3.0, 6);
  auto style = wide();
  style.root_taper = 0.1;
  const auto w = vector::build_wisp(s, 800, style);
  REQUIRE(w);
  const auto& o = w->outline;
  CHECK(std::count(o.side.begin(), o.side.end(), vector::Side::Root) == 0);
  CHECK(o.side.back() == vector::Side::Right);
  CHECK(w->half_width_left.front() == 0);
  CHECK(w->half_width_right.front() == 0);
  CHECK(o.points.front() == s.pixel.front());  // the outline starts and ends at the root
  CHECK((w->sections.front().left - w->sections.front().right).norm() == 0);
  CHECK(signed_area(vector::outline_polygon(*w)) > 0);
  // Full width from 10 % of the strand on.
  CHECK(w->half_width_left[1] > 0);
}

TEST_CASE("band sections stay within the flattening tolerance of the outline cubics",
          "[vector][wisp]") {
  const auto frame = test::random_frame(12, 7);
  const auto style = wide();
  for (const auto& w : vector::build_wisps(frame, style)) {
    // Every outline cubic point lies near the polygon.
    const auto poly = vector::outline_polygon(w);
    for (int i = 0; i < w.outline.piece_count(); ++i)
      for (double u : {0.25, 0.5, 0.75}) {
        const Vector2d p = eval(w.outline.piece(i), u);
        double best = INFINITY;
        for (size_t k = 0; k < poly.size(); ++k) {
          const Vector2d a = poly[k].p, b = poly[(k + 1) % poly.size()].p;
          const double l =
              std::clamp((p - a).dot(b - a) / std::max(1e-300, (b - a).squaredNorm()), 0.0, 1.0);
          best = std::min(best, (a + l * (b - a) - p).norm());
        }
        CHECK(best <= style.flatten_tolerance_px * 1.01);
      }
  }
}

TEST_CASE("width limit keeps each side inside the nearby centres of curvature", "[vector][wisp]") {
  // A tight sine: radius of curvature 30^2 / (4 pi^2 8) = 2.8 px at the crests, against a free
  // half-width of 10 px.
  const auto s = test::strand_from(0, 40, [](double u) {
    return Vector3d(20 + 200 * u, 100 + 8 * std::sin(2 * M_PI * 200 * u / 30), 2.0);
  });
  auto style = wide();
  style.profile = vector::WidthProfile::constant();
  const auto w = vector::build_wisp(s, 800, style);
  REQUIRE(w);
  bool limited = false;
  for (int i = 0; i < w->centre.piece_count(); ++i) {
    const diffusion::Cubic c = w->centre.piece(i);
    const Vector2d d1 = derivative(c, 0), d2 = diffusion::second_derivative(c, 0);
    const double radius = std::pow(d1.norm(), 3) / std::abs(cross(d1, d2));
    // Turning counter-clockwise in (x, y) puts the centre of curvature on the right side.
    const double concave = cross(d1, d2) > 0 ? w->half_width_right[i] : w->half_width_left[i];
    const double convex = cross(d1, d2) > 0 ? w->half_width_left[i] : w->half_width_right[i];
    CHECK(concave <= 0.8 * radius + 1e-9);
    limited |= concave < 9;
    if (radius < 3) CHECK(convex > 9);  // the outer side keeps its width at the crests
  }
  CHECK(limited);
}

TEST_CASE("zero-length, single-sample and fully hidden strands give no wisp", "[vector][wisp]") {
  sim::ProjectedStrand one;
  one.id = 1;
  one.pixel = {{60, 50}};
  one.depth = {2};
  auto frame = test::frame_of({test::straight(0, {50, 50}, {50, 50}, 2, 2, 6), one,
                               test::straight(2, {60, 80}, {160, 80}, 2, 2, 6),
                               test::straight(3, {60, 90}, {160, 90}, 2, 2, 6)});
  frame.strands[3].visible.assign(6, 0);
  const auto wisps = vector::build_wisps(frame, wide());
  REQUIRE(wisps.size() == 1);
  CHECK(wisps[0].strand == 2);
}

TEST_CASE("hidden samples trim the wisp to the longest visible run", "[vector][wisp]") {
  auto s = test::straight(0, {0, 50}, {100, 50}, 2, 2, 11);
  s.visible = {1, 1, 0, 1, 1, 1, 1, 0, 0, 1, 1};
  const auto w = vector::build_wisp(s, 800, wide());
  REQUIRE(w);
  CHECK(w->first_sample == 3);
  CHECK(w->last_sample == 6);
  CHECK(w->centre.points.front().x() == Approx(30));
  CHECK(w->centre.points.back().x() == Approx(60));
  // The profile follows the whole strand: at sample 6 of 10 the taper leaves 40 % of the width.
  CHECK(w->half_width_left.back() == Approx(0.4 * 10).epsilon(1e-9));
}

TEST_CASE("nearly coincident samples are merged, the tip sample kept", "[vector][wisp]") {
  auto s = test::straight(0, {0, 50}, {100, 50}, 2, 2, 6);
  s.pixel.insert(s.pixel.begin() + 3, s.pixel[3] + Vector2d(1e-5, 0));
  s.depth.insert(s.depth.begin() + 3, 2.0);
  s.tangent.insert(s.tangent.begin() + 3, Vector3d::UnitX());
  s.visible.insert(s.visible.begin() + 3, 1);
  const auto w = vector::build_wisp(s, 800, wide());
  REQUIRE(w);
  CHECK(w->centre.piece_count() == 5);
  CHECK(w->centre.points.back() == Vector2d(100, 50));
}

TEST_CASE("bad input is named in an invalid_argument", "[vector][wisp]") {
  auto check_message = [](sim::ProjectedFrame f, const std::string& part) {
    try {
      vector::build_wisps(f, wide());
      FAIL("no exception");
    } catch (const std::invalid_argument& e) {
      INFO(e.what());
      CHECK(std::string(e.what()).find(part) != std::string::npos);
    }
  };
  auto f = test::frame_of({test::straight(7, {0, 0}, {50, 50}, 2, 2, 5)});
  auto nan = f;
  nan.strands[0].pixel[2].x() = NAN;
  check_message(nan, "strand 7: sample 2: pixel is not finite");
  auto depth = f;
  depth.strands[0].depth[1] = 0;
  check_message(depth, "strand 7: sample 1: depth");
  auto sizes = f;
  sizes.strands[0].depth.pop_back();
  check_message(sizes, "strand 7: depth has 4 entries");
  auto focal = f;
  focal.focal_px = 0;
  check_message(focal, "focal_px");
  auto style = wide();
  style.flatten_tolerance_px = -1;
  CHECK_THROWS_AS(vector::build_wisps(f, style), std::invalid_argument);
  style = wide();
  style.width = NAN;
  CHECK_THROWS_AS(vector::build_wisps(f, style), std::invalid_argument);
}

TEST_CASE("absurd coordinates and sizes stay bounded", "[vector][wisp]") {
  // A sample beyond the coordinate limit (a strand crossing the eye plane) is treated as hidden.
  auto s = test::straight(0, {0, 50}, {100, 50}, 2, 2, 6);
  s.pixel[5] = {1e30, 50};
  const auto w = vector::build_wisp(s, 800, wide());
  REQUIRE(w);
  CHECK(w->last_sample == 4);
  // A strand a million pixels long and a huge world width: bounded work, bounded width.
  auto style = wide();
  style.width = 1e6;
  const auto huge = vector::build_wisp(
      test::strand_from(
          0, 8, [](double u) { return Vector3d(-5e5 + 1e6 * u, 1e5 * std::sin(7 * u), 2.0); }),
      800, style);
  REQUIRE(huge);
  CHECK(huge->sections.size() < 20000);
  for (double h : huge->half_width_left) CHECK(h <= style.max_width_px);
}

TEST_CASE("wisp construction is deterministic", "[vector][wisp]") {
  const auto frame = test::random_frame(30, 11);
  const auto a = vector::build_wisps(frame, wide());
  const auto b = vector::build_wisps(frame, wide());
  REQUIRE(a.size() == b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    CHECK(a[i].outline.points == b[i].outline.points);
    REQUIRE(a[i].sections.size() == b[i].sections.size());
    for (size_t k = 0; k < a[i].sections.size(); ++k)
      CHECK(a[i].sections[k].left == b[i].sections[k].left);
  }
}

TEST_CASE("a frame's wisps are those built one at a time", "[vector][wisp]") {
  // build_wisps shares its scratch arrays between the wisps of a frame: a wisp must not see
  // anything of the one before, long or short, curly or straight, with or without clump widths.
  auto frame = test::random_frame(30, 23);
  frame.strands[4].width.assign(frame.strands[4].pixel.size(), 0.03);
  frame.strands[9].visible.assign(frame.strands[9].pixel.size(), 1);
  frame.strands[9].visible[frame.strands[9].visible.size() / 2] = 0;
  std::swap(frame.strands[2], frame.strands[20]);
  const auto style = wide();
  const auto all = vector::build_wisps(frame, style);
  size_t i = 0;
  for (const sim::ProjectedStrand& s : frame.strands) {
    const auto one = vector::build_wisp(s, frame.focal_px, style);
    if (!one) continue;
    REQUIRE(i < all.size());
    const vector::Wisp& w = all[i++];
    CHECK(w.strand == one->strand);
    CHECK(w.centre.points == one->centre.points);
    CHECK(w.half_width_left == one->half_width_left);
    CHECK(w.half_width_right == one->half_width_right);
    CHECK(w.outline.points == one->outline.points);
    CHECK(w.outline.depth == one->outline.depth);
    REQUIRE(w.sections.size() == one->sections.size());
    for (size_t k = 0; k < w.sections.size(); ++k) {
      CHECK(w.sections[k].left == one->sections[k].left);
      CHECK(w.sections[k].right == one->sections[k].right);
      CHECK(w.sections[k].s_left == one->sections[k].s_left);
    }
  }
  CHECK(i == all.size());
}
