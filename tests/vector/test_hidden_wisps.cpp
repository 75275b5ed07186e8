// The cull of hidden wisps before the sweep (vector/hidden_wisps.hpp): a wisp hidden by several
// nearer wisps together is left out and the outputs stay the same; a wisp that shows anywhere,
// even through a gap narrower than the cull's squares, or nearer than its cover at one end, is
// kept.
#include <catch2/catch.hpp>
#include <cmath>

#include "tests/vector/scenes.hpp"
#include "vector/arrangement.hpp"
#include "vector/wisp.hpp"

using namespace wisp;
using Eigen::Vector2d;

namespace {

vector::Wisp band(int id, Vector2d a, Vector2d b, double za, double zb, double width) {
  vector::WispStyle s;
  s.width = width;
  s.profile = vector::WidthProfile::constant();
  s.root_taper = 0;
  auto w = vector::build_wisp(test::straight(id, a, b, za, zb, 8), 800, s);
  REQUIRE(w);
  return *w;
}

vector::WispArrangement arrange(const std::vector<vector::Wisp>& wisps, bool cull) {
  vector::ArrangementOptions o;
  o.view = vector::image_rect(512, 512);
  o.cull_hidden = cull;
  return vector::build_arrangement(wisps, o);
}

void check_same_outputs(const vector::WispArrangement& on, const vector::WispArrangement& off) {
  REQUIRE(on.visible.size() == off.visible.size());
  for (size_t w = 0; w < on.visible.size(); ++w) {
    INFO("wisp " << w);
    REQUIRE(on.visible[w].size() == off.visible[w].size());
    for (size_t i = 0; i < on.visible[w].size(); ++i) {
      CHECK(on.visible[w][i].first == Approx(off.visible[w][i].first).margin(1e-9));
      CHECK(on.visible[w][i].second == Approx(off.visible[w][i].second).margin(1e-9));
    }
  }
  REQUIRE(on.mask.polygons.size() == off.mask.polygons.size());
  for (size_t p = 0; p < on.mask.polygons.size(); ++p) {
    CHECK(on.mask.polygons[p].outer == off.mask.polygons[p].outer);
    CHECK(on.mask.polygons[p].holes == off.mask.polygons[p].holes);
  }
  CHECK(on.silhouette.size() == off.silhouette.size());
  CHECK(on.occlusion.size() == off.occlusion.size());
}

}  // namespace

TEST_CASE("a wisp hidden by two nearer wisps together is culled", "[vector][cull]") {
  // Two 40 px bands at depth 2 overlap over x in [200, 240]; the 10 px band at depth 3 under them
  // runs from x 120 to 320: neither covers it alone.
  const auto k1 = band(0, {100, 200}, {240, 200}, 2, 2, 0.1);
  const auto k2 = band(1, {200, 205}, {400, 205}, 2, 2, 0.1);
  const auto d = band(2, {120, 202}, {320, 202}, 3, 3, 0.025);
  const auto on = arrange({k1, k2, d}, true), off = arrange({k1, k2, d}, false);
  CHECK(on.stats.hidden_wisps == 1);
  CHECK(on.stats.hidden_segments > 0);
  CHECK(on.stats.wisps == 2);
  CHECK(off.stats.hidden_wisps == 0);
  CHECK(on.stats.faces < off.stats.faces);
  CHECK(off.visible[2].empty());
  check_same_outputs(on, off);
}

TEST_CASE("a wisp that shows through a gap narrower than a square is kept", "[vector][cull]") {
  // The same bands 0.5 px apart: the far band shows in the gap between them.
  const auto k1 = band(0, {100, 200}, {240, 200}, 2, 2, 0.1);
  const auto k2 = band(1, {240.5, 200}, {400, 200}, 2, 2, 0.1);
  const auto d = band(2, {120, 200}, {320, 200}, 3, 3, 0.025);
  const auto on = arrange({k1, k2, d}, true), off = arrange({k1, k2, d}, false);
  CHECK(on.stats.hidden_wisps == 0);
  CHECK(!off.visible[2].empty());
  check_same_outputs(on, off);

  // Inside one band all along, but nearer than it at one end: kept. (Its inside is one face,
  // whose front the resolver decides at one sample, where the band is nearer; the cull does not
  // lean on that.)
  const auto k = band(0, {100, 200}, {400, 200}, 2, 2, 0.1);
  const auto rising = band(1, {120, 200}, {380, 200}, 1.9, 3, 0.025);
  const auto r_on = arrange({k, rising}, true), r_off = arrange({k, rising}, false);
  CHECK(r_on.stats.hidden_wisps == 0);
  check_same_outputs(r_on, r_off);
}

TEST_CASE("the hidden cells of a wisp that shows are cut out of the sweep", "[vector][cull]") {
  // A far wavy band (many cells) crossing under a wide near band: its middle is hidden, both its
  // ends show.
  const auto k = band(0, {250, 100}, {250, 300}, 2, 2, 0.15);
  vector::WispStyle style;
  style.width = 0.025;
  const auto wavy = vector::build_wisp(
      test::strand_from(
          1, 24,
          [](double u) { return Eigen::Vector3d(100 + 300 * u, 200 + 3 * std::sin(20 * u), 3); }),
      800, style);
  REQUIRE(wavy);
  const auto& d = *wavy;
  const auto on = arrange({k, d}, true), off = arrange({k, d}, false);
  CHECK(on.stats.hidden_wisps == 0);
  CHECK(on.stats.cuts == 2);  // one line across the band at each end of the hidden run
  CHECK(on.stats.hidden_segments > 0);
  CHECK(on.stats.segments < off.stats.segments);
  CHECK(!on.visible[1].empty());
  check_same_outputs(on, off);

  // The cuts are hidden, carry no outline parameter, and no ink runs along them.
  vector::ArrangementOptions o;
  o.view = vector::image_rect(512, 512);
  o.keep_faces = true;
  const auto view = vector::build_arrangement({k, d}, o).view;
  int cut_edges = 0;
  for (const auto& e : view.edges)
    for (const auto& s : e.sources)
      if (s.cut) {
        ++cut_edges;
        CHECK(s.wisp == 1);
        CHECK(!s.visible);
        CHECK(s.s0 == s.s1);
        CHECK(!e.silhouette);
        CHECK(!e.occlusion);
      }
  CHECK(cut_edges >= 2);
  o.cut_hidden = false;
  CHECK(vector::build_arrangement({k, d}, o).stats.cuts == 0);
}
