// The cases Faraj's pairwise rule gets wrong or never considered, each as the smallest scene that
// shows it: many crossings per pair, containment, a cyclic overlap, tangent and coincident
// outlines, degenerate and off-screen strands, a hole ringed by wisps, a curl over itself.
#include <catch2/catch.hpp>
#include <cmath>

#include "tests/vector/scenes.hpp"
#include "vector/arrangement.hpp"
#include "vector/wisp.hpp"

using namespace wisp;
using Eigen::Vector2d;
using Eigen::Vector3d;

namespace {

vector::WispStyle style_with(double width) {
  vector::WispStyle s;
  s.width = width;
  s.profile = vector::WidthProfile::constant();
  s.root_taper = 0;  // bands of exactly known width, cut square at both ends
  return s;
}

vector::Wisp wisp_of(const sim::ProjectedStrand& s, double width = 0.05) {
  auto w = vector::build_wisp(s, 800, style_with(width));
  REQUIRE(w);
  return *w;
}

// Without the cull of hidden wisps (tested on its own in test_hidden_wisps.cpp), so that every
// wisp's coverage and visibility are decided by the arrangement.
vector::WispArrangement arrange(const std::vector<vector::Wisp>& wisps, bool clip = true) {
  vector::ArrangementOptions o;
  o.view = vector::image_rect(512, 512);
  o.clip_to_view = clip;
  o.keep_faces = true;
  o.cull_hidden = false;
  return vector::build_arrangement(wisps, o);
}

bool inside(const std::vector<Vector2d>& ring, const Vector2d& p) {
  bool in = false;
  for (size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++)
    if ((ring[i].y() > p.y()) != (ring[j].y() > p.y()) &&
        p.x() < ring[j].x() + (p.y() - ring[j].y()) * (ring[i].x() - ring[j].x()) /
                                  (ring[i].y() - ring[j].y()))
      in = !in;
  return in;
}

// The face containing p (p must not lie on an edge).
const vector::ViewFace& face_at(const vector::ArrangementView& v, const Vector2d& p) {
  for (const auto& f : v.faces) {
    if (f.unbounded || !inside(f.outer, p)) continue;
    bool in_hole = false;
    for (const auto& h : f.holes) in_hole |= inside(h, p);
    if (!in_hole) return f;
  }
  for (const auto& f : v.faces)
    if (f.unbounded) return f;
  FAIL("no unbounded face");
  return v.faces[0];
}

int winding(const vector::ViewFace& f, int wisp) {
  for (auto [w, n] : f.cover)
    if (w == wisp) return n;
  return 0;
}

double ring_area(const std::vector<Vector2d>& r) {
  double a = 0;
  for (size_t i = 0, j = r.size() - 1; i < r.size(); j = i++)
    a += r[j].x() * r[i].y() - r[i].x() * r[j].y();
  return a / 2;
}

// Strand through p1 (depth z1) and p2 (depth z2), extended by 60 % beyond both.
sim::ProjectedStrand through(int id, Vector2d p1, Vector2d p2, double z1, double z2) {
  return test::straight(id, p1 - 0.6 * (p2 - p1), p2 + 0.6 * (p2 - p1), z1 - 0.6 * (z2 - z1),
                        z2 + 0.6 * (z2 - z1), 8);
}

}  // namespace

TEST_CASE("a pair crossing four times with depth order changing along the way", "[vector][hard]") {
  // A straight at depth 3; B waves across it four times while receding from depth 2 to 4, so it is
  // in front at the first two crossings and behind at the last two.
  const auto a = wisp_of(test::straight(0, {20, 200}, {300, 200}, 3, 3, 8), 0.03);
  const auto b =
      wisp_of(test::strand_from(1, 60,
                                [](double u) {
                                  return Vector3d(40 + 240 * u, 200 + 40 * std::cos(4 * M_PI * u),
                                                  2 + 2 * u);
                                }),
              0.03);
  const auto arr = arrange({a, b});
  for (double u : {0.125, 0.375, 0.625, 0.875}) {
    const auto& f = face_at(arr.view, {40 + 240 * u, 200});
    CHECK(winding(f, 0) == 1);
    CHECK(winding(f, 1) == 1);
    CHECK(f.front == (u < 0.5 ? 1 : 0));
  }
  // Each wisp is hidden at two crossings, on both of its sides: five visible pieces each.
  CHECK(arr.visible[0].size() == 5);
  CHECK(arr.visible[1].size() == 5);
}

TEST_CASE("containment without crossings, in front and behind", "[vector][hard]") {
  const auto big = wisp_of(test::straight(0, {50, 100}, {350, 100}, 2, 2, 6), 0.05);  // 10 px
  for (double z : {1.5, 3.0}) {
    const auto small = wisp_of(test::straight(1, {150, 100}, {200, 100}, z, z, 4), 0.01);
    const auto arr = arrange({big, small});
    const auto& f = face_at(arr.view, {175, 100});
    CHECK(winding(f, 0) == 1);
    CHECK(winding(f, 1) == 1);
    REQUIRE(arr.mask.polygons.size() == 1);
    CHECK(arr.mask.polygons[0].holes.empty());
    REQUIRE(arr.visible[0].size() == 1);  // the big wisp has nothing in front of it
    CHECK(arr.visible[0][0].first == Approx(0).margin(1e-9));
    CHECK(arr.visible[0][0].second == Approx(1).margin(1e-9));
    if (z < 2) {
      CHECK(f.front == 1);
      REQUIRE(arr.visible[1].size() == 1);
      CHECK(arr.visible[1][0].second - arr.visible[1][0].first == Approx(1).margin(1e-9));
      CHECK(arr.occlusion.size() == 1);
      CHECK(arr.occlusion[0].closed);
    } else {
      CHECK(f.front == 0);
      CHECK(arr.visible[1].empty());
      CHECK(arr.occlusion.empty());
      // The cull proves it hidden and leaves it out; the big wisp's outputs stay.
      vector::ArrangementOptions o;
      o.view = vector::image_rect(512, 512);
      const auto culled = vector::build_arrangement({big, small}, o);
      CHECK(culled.stats.hidden_wisps == 1);
      CHECK(culled.visible == arr.visible);
    }
  }
}

TEST_CASE("a cyclic overlap: A over B over C over A", "[vector][hard]") {
  const Vector2d ab(150, 100), bc(250, 250), ca(100, 250);
  const auto a = wisp_of(through(0, ab, ca, 2, 4), 0.02);
  const auto b = wisp_of(through(1, ab, bc, 3, 2), 0.02);
  const auto c = wisp_of(through(2, bc, ca, 3, 2), 0.02);
  const auto arr = arrange({a, b, c});
  CHECK(face_at(arr.view, ab).front == 0);
  CHECK(face_at(arr.view, bc).front == 1);
  CHECK(face_at(arr.view, ca).front == 2);
  // Each wisp is under one other at one crossing: its outline is cut there on both sides.
  for (int w = 0; w < 3; ++w) CHECK(arr.visible[w].size() == 3);
}

TEST_CASE("tangent wisps sharing part of an edge, and touching at one point", "[vector][hard]") {
  // 10 px half-widths: A covers y in [90,110], B [110,130] over x in [100,250]; C touches A's
  // corner (250,110) only.
  const auto a = wisp_of(test::straight(0, {50, 100}, {250, 100}, 2, 2, 5));
  const auto b = wisp_of(test::straight(1, {100, 120}, {300, 120}, 2, 2, 5));
  const auto arr = arrange({a, b});
  for (const auto& f : arr.view.faces) CHECK(f.cover.size() <= 1);
  CHECK(face_at(arr.view, {175, 105}).front == 0);
  CHECK(face_at(arr.view, {175, 115}).front == 1);
  REQUIRE(arr.mask.polygons.size() == 1);
  CHECK(arr.mask.polygons[0].holes.empty());
  CHECK(std::abs(ring_area(arr.mask.polygons[0].outer)) ==
        Approx(200 * 20 + 200 * 20).epsilon(1e-6));
  int shared = 0;
  for (const auto& e : arr.view.edges) {
    if (e.sources.size() != 2) continue;
    ++shared;
    CHECK(e.a.y() == Approx(110));
    for (const auto& s : e.sources) CHECK(s.visible);
    CHECK(e.occlusion);
  }
  CHECK(shared >= 1);

  const auto c = wisp_of(test::straight(2, {250, 120}, {450, 120}, 2, 2, 5));
  const auto touch = arrange({a, c});
  CHECK(touch.mask.polygons.size() == 2);
  bool corner = false;
  for (const auto& v : touch.view.vertices)
    corner |= v.p == Vector2d(250, 110) && v.intersection && v.degree == 4;
  CHECK(corner);
}

TEST_CASE("coincident duplicate strands: the lower index wins, the copy is hidden",
          "[vector][hard]") {
  const auto s = test::strand_from(
      5, 12, [](double u) { return Vector3d(60 + 200 * u, 150 + 30 * std::sin(5 * u), 2.5); });
  auto copy = s;
  copy.id = 6;
  const auto wisps = vector::build_wisps(test::frame_of({s, copy}), style_with(0.05));
  REQUIRE(wisps.size() == 2);
  const auto arr = arrange(wisps);
  for (const auto& e : arr.view.edges) {
    if (e.sources.size() == 1 && e.sources[0].wisp < 0) continue;  // view frame
    REQUIRE(e.sources.size() == 2);
  }
  for (const auto& f : arr.view.faces)
    if (!f.cover.empty()) {
      CHECK(f.cover.size() == 2);
      CHECK(f.front == 0);
    }
  REQUIRE(arr.visible[0].size() == 1);
  CHECK(arr.visible[0][0].second - arr.visible[0][0].first == Approx(1).margin(1e-9));
  CHECK(arr.visible[1].empty());
  CHECK(arr.mask.polygons.size() == 1);
}

TEST_CASE("a zero-length strand among others is skipped end to end", "[vector][hard]") {
  const auto frame = test::frame_of({test::straight(0, {80, 80}, {80, 80}, 2, 2, 6),
                                     test::straight(1, {50, 100}, {250, 100}, 2, 2, 6)});
  const auto wisps = vector::build_wisps(frame, style_with(0.05));
  REQUIRE(wisps.size() == 1);
  const auto arr = arrange(wisps);
  CHECK(arr.stats.wisps == 1);
  CHECK(arr.mask.polygons.size() == 1);
  REQUIRE(arr.visible[0].size() == 1);
}

TEST_CASE("a wisp entirely off-screen changes nothing and one partly off-screen is clipped",
          "[vector][hard]") {
  const auto a = wisp_of(test::straight(0, {100, 100}, {300, 150}, 2, 2, 6));
  const auto off = wisp_of(test::straight(1, {-600, 100}, {-400, 150}, 1, 1, 6));
  const auto alone = arrange({a});
  const auto both = arrange({a, off});
  CHECK(both.stats.wisps == 1);
  CHECK(both.visible[1].empty());
  CHECK(both.stats.faces == alone.stats.faces);
  CHECK(both.visible[0] == alone.visible[0]);

  // Crossing the left border: the mask stays inside the image, the outline is visible only there.
  const auto part = wisp_of(test::straight(2, {-100, 300}, {150, 300}, 2, 2, 6));
  const auto arr = arrange({part});
  REQUIRE(arr.mask.polygons.size() == 1);
  for (const auto& p : arr.mask.polygons[0].outer) CHECK(p.x() >= 0);
  CHECK(std::abs(ring_area(arr.mask.polygons[0].outer)) == Approx(150 * 20).epsilon(1e-6));
  REQUIRE(!arr.visible[0].empty());
  for (const auto& v : vector::outline_polygon(part)) {
    bool vis = false;
    for (auto [s0, s1] : arr.visible[0]) vis |= v.s > s0 + 1e-9 && v.s < s1 - 1e-9;
    if (vis) CHECK(v.p.x() >= -1e-9);
  }
  // No ink along the image border.
  for (const auto& line : arr.silhouette)
    for (size_t i = 0; i + 1 < line.points.size(); ++i)
      CHECK(!(line.points[i].x() == 0 && line.points[i + 1].x() == 0));
}

TEST_CASE("a hole ringed by four wisps stays a hole", "[vector][hard]") {
  // Bars 20 px wide around the square (110,190)^2.
  const auto frame = test::frame_of({test::straight(0, {50, 100}, {250, 100}, 2, 2, 5),
                                     test::straight(1, {50, 200}, {250, 200}, 2, 2, 5),
                                     test::straight(2, {100, 50}, {100, 250}, 2.2, 2.2, 5),
                                     test::straight(3, {200, 50}, {200, 250}, 1.8, 1.8, 5)});
  auto style = style_with(0.05);
  const auto wisps = vector::build_wisps(frame, style);
  const auto arr = arrange(wisps);
  REQUIRE(arr.mask.polygons.size() == 1);
  REQUIRE(arr.mask.polygons[0].holes.size() == 1);
  const auto& hole = arr.mask.polygons[0].holes[0];
  CHECK(ring_area(hole) < 0);  // holes turn clockwise in (x, y)
  // Bars 2 and 3 are nearer or farther, so narrower or wider: the hole is their gap.
  const double h2 = 0.5 * 0.05 * 800 / 2.2, h3 = 0.5 * 0.05 * 800 / 1.8;
  CHECK(std::abs(ring_area(hole)) == Approx((100 - h2 - h3) * 80).epsilon(1e-6));
  const auto& f = face_at(arr.view, {150, 150});
  CHECK(!f.unbounded);  // "all bounded faces" would have filled it
  CHECK(f.cover.empty());
  CHECK(f.front == -1);
  // The hole's rim is silhouette: its ink has the hole's perimeter.
  double rim = 0;
  for (const auto& line : arr.silhouette) {
    bool on_rim = true;
    for (const auto& p : line.points)
      on_rim &= p.x() > 105 && p.x() < 195 && p.y() > 105 && p.y() < 195;
    if (!on_rim) continue;
    for (size_t i = 0; i + 1 < line.points.size(); ++i)
      rim += (line.points[i + 1] - line.points[i]).norm();
    if (line.closed) rim += (line.points.front() - line.points.back()).norm();
  }
  CHECK(rim == Approx(2 * (100 - h2 - h3) + 2 * 80).epsilon(1e-6));
}

TEST_CASE("a curl over itself hides its own back pass", "[vector][hard]") {
  // A trochoid loop: the strand crosses itself at (150, 169.5); depth grows along the strand, so
  // the early pass is in front there.
  const auto s = test::strand_from(0, 40, [](double u) {
    const double t = -M_PI + 2 * M_PI * u;
    return Vector3d(150 + 10 * t - 30 * std::sin(t), 150 - 30 * std::cos(t), 2 + u);
  });
  const auto w = wisp_of(s, 0.02);
  const auto arr = arrange({w});
  const auto& f = face_at(arr.view, {150, 169.5});
  CHECK(winding(f, 0) == 2);
  CHECK(f.front == 0);
  // Left and right side of the back pass are hidden inside the front pass.
  CHECK(arr.visible[0].size() == 3);
  REQUIRE(arr.mask.polygons.size() == 1);
}

TEST_CASE("arrangement input errors are named", "[vector][hard]") {
  auto w = wisp_of(test::straight(0, {50, 100}, {250, 100}, 2, 2, 5));
  vector::ArrangementOptions o;  // empty view with clipping on
  CHECK_THROWS_AS(vector::build_arrangement({w}, o), std::invalid_argument);
  o.view = vector::image_rect(512, 512);
  auto bad = w;
  bad.sections[1].left.x() = NAN;
  CHECK_THROWS_WITH(vector::build_arrangement({w, bad}, o), Catch::Contains("wisp 1"));
  const auto empty = vector::build_arrangement({}, o);
  CHECK(empty.stats.faces == 2);  // the view frame's inside and the unbounded face
  CHECK(empty.mask.polygons.empty());
}
