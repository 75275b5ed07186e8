// Depth seams (vector/depth_seams.hpp) and the depth they follow (vector/band_depth.hpp): the
// band's depth is continuous across its cells; two wisps that swap depth order inside their overlap
// get a seam there, and each side takes its own front; on random frames every point of every hair
// face has the face's front as its nearest covering wisp, with the hidden-wisp cull on or off,
// which without the seams does not hold.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <random>

#include "tests/vector/scenes.hpp"
#include "vector/arrangement.hpp"
#include "vector/band_depth.hpp"
#include "vector/depth_seams.hpp"
#include "vector/front_check.hpp"
#include "vector/polygon.hpp"
#include "vector/wisp.hpp"

using namespace wisp;
using Eigen::Vector2d;
using Eigen::Vector3d;

namespace {

vector::Wisp wisp_of(const sim::ProjectedStrand& s, double width) {
  vector::WispStyle style;
  style.width = width;
  style.profile = vector::WidthProfile::constant();
  style.root_taper = 0;
  auto w = vector::build_wisp(s, 800, style);
  REQUIRE(w);
  return *w;
}

vector::WispArrangement arrange(const std::vector<vector::Wisp>& wisps, bool seams, bool cull) {
  vector::ArrangementOptions o;
  o.view = vector::image_rect(512, 512);
  o.keep_faces = true;
  o.depth_seams = seams;
  o.cull_hidden = cull;
  return vector::build_arrangement(wisps, o);
}

// `count` wavy strands crowded into the middle of a 512 px frame at nearly the same depth, each
// dipping back and forth along its length: many overlapping pairs swap depth order.
std::vector<vector::Wisp> tangle(int count, std::uint32_t seed) {
  std::mt19937 rng(seed);
  const auto uni = [&](double a, double b) {
    return std::uniform_real_distribution<double>(a, b)(rng);
  };
  std::vector<sim::ProjectedStrand> strands;
  for (int i = 0; i < count; ++i) {
    const Vector2d root(uni(150, 350), uni(150, 350));
    const double angle = uni(0, 2 * M_PI), length = uni(80, 160), phase = uni(0, 2 * M_PI);
    const double z0 = uni(2, 2.1), dip = uni(0.02, 0.1);
    const Vector2d dir(std::cos(angle), std::sin(angle)), normal(-dir.y(), dir.x());
    strands.push_back(test::strand_from(i, 24, [=](double u) {
      const Vector2d p = root + length * u * dir + 6 * std::sin(8 * u + phase) * normal;
      return Vector3d(p.x(), p.y(), z0 + dip * std::sin(5 * u + phase));
    }));
  }
  vector::WispStyle style;
  style.width = 0.04;
  return vector::build_wisps(test::frame_of(strands), style);
}

}  // namespace

TEST_CASE("a band's depth is continuous across its cells", "[vector][seams]") {
  // A wavy strand receding from depth 2 to 4: across every section line between two cells, the
  // depth just before and just after it agree.
  const auto w = wisp_of(
      test::strand_from(
          0, 40,
          [](double u) { return Vector3d(60 + 300 * u, 200 + 30 * std::sin(6 * u), 2 + 2 * u); }),
      0.06);
  REQUIRE(w.sections.size() > 10);
  double worst = 0;
  for (size_t i = 1; i + 1 < w.sections.size(); ++i) {
    const vector::Section& s = w.sections[i];
    const Vector2d along = (w.sections[i + 1].centre - w.sections[i - 1].centre).normalized();
    for (double f : {0.2, 0.5, 0.8}) {
      const Vector2d p = s.left + f * (s.right - s.left);
      const double before = vector::band_depth(w, p - 1e-7 * along).depth;
      const double after = vector::band_depth(w, p + 1e-7 * along).depth;
      worst = std::max(worst, std::abs(after - before));
      CHECK(before == Approx(s.depth).epsilon(1e-6));
    }
  }
  CHECK(worst < 1e-6);
}

TEST_CASE("two wisps swapping depth inside their overlap are split by a seam", "[vector][seams]") {
  // Two 12 px bands along the same line, 4 px apart: A recedes from depth 2 to 4, B comes nearer
  // from 4 to 2. Their outlines never cross, so without seams the overlap is one face with one
  // front; in fact A is in front on the left half and B on the right.
  const auto a = wisp_of(test::straight(0, {60, 200}, {360, 200}, 2, 4, 8), 0.03);
  const auto b = wisp_of(test::straight(1, {60, 204}, {360, 204}, 4, 2, 8), 0.03);
  const Vector2d left(120, 202), right(300, 202);

  const auto with = arrange({a, b}, true, false);
  CHECK(with.stats.seam_segments > 0);
  const auto front_at = [](const vector::WispArrangement& arr, const Vector2d& p) {
    for (const vector::ViewFace& f : arr.view.faces) {
      if (f.outer.empty() || !vector::inside_polygon(f.outer, p)) continue;
      if (std::none_of(f.holes.begin(), f.holes.end(),
                       [&](const auto& h) { return vector::inside_polygon(h, p); }))
        return f.front;
    }
    return -2;
  };
  CHECK(front_at(with, left) == 0);
  CHECK(front_at(with, right) == 1);
  // The seam is no outline: it splits faces without drawing an ink line along itself.
  for (const vector::InkLine& line : with.occlusion)
    for (const Vector2d& p : line.points) CHECK(std::abs(p.y() - 202) > 1.5);

  const auto without = arrange({a, b}, false, false);
  CHECK(without.stats.seam_segments == 0);
  CHECK(front_at(without, left) == front_at(without, right));
}

TEST_CASE("every point of a hair face has the face's front", "[vector][seams]") {
  for (std::uint32_t seed : {3u, 11u}) {
    const auto wisps = tangle(40, seed);
    INFO("seed " << seed);
    for (bool cull : {false, true}) {
      INFO("cull " << cull);
      const auto arr = arrange(wisps, true, cull);
      const vector::FrontCheck c = vector::check_fronts(wisps, arr.view, {});
      CHECK(c.points > 1000);
      CHECK(c.wrong_points == 0);
      // With the cull, the hidden cells of the wisps kept are cut out of the sweep too.
      CHECK((arr.stats.cuts > 0) == cull);
    }
    // Without the seams the one sample per face is wrong somewhere: the scene tests the seams.
    const vector::FrontCheck off =
        vector::check_fronts(wisps, arrange(wisps, false, false).view, {});
    CHECK(off.wrong_faces > 0);
  }
}

TEST_CASE("where hair passes behind an occluder the faces are split there too", "[vector][seams]") {
  // A tilted disc of radius 60 through the tangle's depths, inside a square ring (the occluders'
  // rings are convex hulls, which can bulge past the surface: the eye rays miss it there).
  const Vector2d centre(250, 250);
  vector::Occluder disc;
  disc.ring = {{180, 180}, {320, 180}, {320, 320}, {180, 320}};
  disc.depth = [centre](const Vector2d& p) {
    return (p - centre).norm() < 60 ? 2.05 + 0.001 * (p.x() - centre.x()) : INFINITY;
  };
  vector::FrontCheckOptions away;  // from the rim, by about a third of a triangle
  away.skip = [centre](const Vector2d& p) { return std::abs((p - centre).norm() - 60) < 5; };
  for (std::uint32_t seed : {3u, 11u}) {
    INFO("seed " << seed);
    const auto wisps = tangle(40, seed);
    vector::ArrangementOptions o;
    o.view = vector::image_rect(512, 512);
    o.keep_faces = true;
    o.occluders = {disc};
    const auto with = vector::build_arrangement(wisps, o);
    // The seams follow the depths exactly (both affine over a wisp's triangle). Across the rim
    // they join the points where a triangle's edges cross it by straight lines, and a triangle
    // whose corners all miss the disc gets none: within a triangle's size (about 16 px here) of
    // the rim some points may take the other side's front.
    const vector::FrontCheck c = vector::check_fronts(wisps, with.view, {disc}, away);
    CHECK(c.points > 1000);
    CHECK(c.wrong_points == 0);
    o.occluder_seams = false;
    const vector::FrontCheck off =
        vector::check_fronts(wisps, vector::build_arrangement(wisps, o).view, {disc}, away);
    CHECK(off.wrong_faces > 0);
    CHECK(with.stats.seam_segments > vector::build_arrangement(wisps, o).stats.seam_segments);
  }
}

TEST_CASE("depth seams are deterministic and skip hidden cells", "[vector][seams]") {
  const auto wisps = tangle(30, 5);
  const std::vector<char> used(wisps.size(), 1);
  const auto view = vector::image_rect(512, 512);
  const auto first = vector::depth_seams(wisps, used, {}, {}, -2, view);
  const auto again = vector::depth_seams(wisps, used, {}, {}, -2, view);
  REQUIRE(first.size() == again.size());
  REQUIRE(!first.empty());
  for (size_t i = 0; i < first.size(); ++i) {
    CHECK(first[i].a == again[i].a);
    CHECK(first[i].b == again[i].b);
    CHECK(first[i].wisp == -2);
  }
  // Every cell hidden: no seam. Every cell of one wisp hidden: fewer seams.
  std::vector<std::vector<char>> hidden(wisps.size());
  for (size_t w = 0; w < wisps.size(); ++w) hidden[w].assign(wisps[w].sections.size() - 1, 1);
  CHECK(vector::depth_seams(wisps, used, hidden, {}, -2, view).empty());
  size_t busiest = 0, most = 0;
  for (size_t w = 0; w < wisps.size(); ++w) {
    // Seams of wisp w: all seams minus those without it.
    std::vector<char> others(wisps.size(), 1);
    others[w] = 0;
    const size_t with_w =
        first.size() - vector::depth_seams(wisps, others, {}, {}, -2, view).size();
    if (with_w > most) most = with_w, busiest = w;
  }
  REQUIRE(most > 0);
  std::vector<std::vector<char>> one(wisps.size());
  one[busiest].assign(wisps[busiest].sections.size() - 1, 1);
  CHECK(vector::depth_seams(wisps, used, one, {}, -2, view).size() == first.size() - most);
}

TEST_CASE("seams of bands reaching far beyond the view stay few and in place", "[vector][seams]") {
  // Two bands 100 000 px long, crossing the 512 px view, swapping depth in its middle: the grid
  // of the pair search is sized by the triangles, not by their spread.
  const auto a = wisp_of(test::straight(0, {-50000, 250}, {50000, 250}, 2, 4, 64), 0.03);
  const auto b = wisp_of(test::straight(1, {-50000, 253}, {50000, 253}, 4, 2, 64), 0.03);
  const std::vector<char> used = {1, 1};
  const auto seams = vector::depth_seams({a, b}, used, {}, {}, -2, vector::image_rect(512, 512));
  REQUIRE(!seams.empty());
  for (const vector::OutlineSegment& s : seams) {
    // The bands' depths meet at x = 0 on the centre line; across the overlap the seam stays near.
    CHECK(std::abs(s.a.x()) < 600);
    CHECK(std::abs(s.b.x()) < 600);
  }
  const auto arr = arrange({a, b}, true, true);
  CHECK(arr.stats.seam_segments > 0);
}
