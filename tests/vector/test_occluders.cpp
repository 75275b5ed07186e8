// Occluders (the head and body): hair that passes behind one is cut exactly along its
// silhouette; hair in front of it is untouched; depth decides per face.
#include <catch2/catch.hpp>
#include <cmath>

#include "tests/vector/scenes.hpp"
#include "vector/arrangement.hpp"

using namespace wisp;
using Eigen::Vector2d;

namespace {

double ring_area(const std::vector<Vector2d>& ring) {
  double a = 0;
  for (size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++)
    a += ring[j].x() * ring[i].y() - ring[i].x() * ring[j].y();
  return 0.5 * std::abs(a);
}

double mask_area(const vector::HairMask& m) {
  double a = 0;
  for (const auto& p : m.polygons) {
    a += ring_area(p.outer);
    for (const auto& h : p.holes) a -= ring_area(h);
  }
  return a;
}

// A square from (x0,y0) to (x1,y1) with a constant depth.
vector::Occluder square(double x0, double y0, double x1, double y1, double depth) {
  vector::Occluder o;
  o.ring = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
  o.depth = [depth](const Vector2d&) { return depth; };
  return o;
}

vector::Wisp band(double depth) {
  // A straight wisp 20 px wide from x = 100 to x = 400 at y = 200 (constant width profile).
  vector::WispStyle s;
  s.width = 0.05 * depth / 2;  // 800 px focal length: 20 px full width at any depth
  s.profile = vector::WidthProfile::constant();
  s.root_taper = 0;
  auto w = vector::build_wisp(test::straight(0, {100, 200}, {400, 200}, depth, depth, 8), 800, s);
  REQUIRE(w);
  return *w;
}

vector::WispArrangement arrange(const std::vector<vector::Wisp>& wisps,
                                std::vector<vector::Occluder> occluders) {
  vector::ArrangementOptions o;
  o.view = vector::image_rect(512, 512);
  o.occluders = std::move(occluders);
  o.keep_faces = true;
  return vector::build_arrangement(wisps, o);
}

}  // namespace

TEST_CASE("hair behind an occluder is cut exactly along its silhouette", "[vector][occluder]") {
  const auto w = band(4.0);
  const double full = mask_area(arrange({w}, {}).mask);
  CHECK(full == Approx(300 * 20).epsilon(0.01));
  // The square covers x in [200, 260] over the whole band, nearer the eye than the hair.
  const auto behind = arrange({w}, {square(200, 150, 260, 250, 2.0)});
  CHECK(mask_area(behind.mask) == Approx(full - 60 * 20).epsilon(0.001));
  // The outline (root, one side to the tip, the other side back) is hidden inside the square on
  // each side: visible in three intervals, the last wrapping around to the first at the root.
  REQUIRE(behind.visible[0].size() == 3);
  CHECK(behind.visible[0].front().first == Approx(0).margin(1e-9));
  CHECK(behind.visible[0].back().second == Approx(1).margin(1e-9));
  // The cut edges are silhouette (ink) lines: along x = 200 and x = 260.
  bool at200 = false, at260 = false;
  for (const auto& line : behind.silhouette)
    for (const auto& p : line.points) {
      at200 |= std::abs(p.x() - 200) < 1e-6 && std::abs(p.y() - 200) <= 10.5;
      at260 |= std::abs(p.x() - 260) < 1e-6 && std::abs(p.y() - 200) <= 10.5;
    }
  CHECK(at200);
  CHECK(at260);
  // Nothing of the occluder leaks into the debug view as a wisp.
  for (const auto& e : behind.view.edges)
    for (const auto& s : e.sources) CHECK(s.wisp < 1);
}

TEST_CASE("hair in front of an occluder is untouched", "[vector][occluder]") {
  const auto w = band(1.0);
  const auto front = arrange({w}, {square(200, 150, 260, 250, 2.0)});
  CHECK(mask_area(front.mask) == Approx(300 * 20).epsilon(0.01));
  REQUIRE(front.visible[0].size() == 1);
  CHECK(front.visible[0][0].first == Approx(0).margin(1e-9));
  CHECK(front.visible[0][0].second == Approx(1).margin(1e-9));
}

TEST_CASE("an occluder's depth decides per face, and a miss counts as far", "[vector][occluder]") {
  // Depth 1 on the left half of the square, no surface (a miss) on the right half.
  vector::Occluder o = square(200, 150, 260, 250, 0);
  o.depth = [](const Vector2d& p) { return p.x() < 230 ? 1.0 : INFINITY; };
  // A vertical wisp at x = 215 and one at x = 245, both crossing the square's middle row.
  vector::WispStyle s;
  s.width = 0.05;
  s.profile = vector::WidthProfile::constant();
  s.root_taper = 0;
  const auto a = vector::build_wisp(test::straight(0, {215, 100}, {215, 300}, 2, 2, 8), 800, s);
  const auto b = vector::build_wisp(test::straight(1, {245, 100}, {245, 300}, 2, 2, 8), 800, s);
  const auto arr = arrange({*a, *b}, {o});
  CHECK(arr.visible[0].size() == 3);  // cut by the near half (on both of its sides)
  CHECK(arr.visible[1].size() == 1);  // the far half hides nothing
}
