// Topology: curly and wavy outlines do not cross themselves thanks to the width limit (and do
// without it), and the flattened segment arrangement has the same faces as CGAL's exact Bezier
// arrangement of the outline cubics on small scenes.
#include <catch2/catch.hpp>
#include <cmath>

#include "tests/vector/scenes.hpp"
#include "vector/arrangement.hpp"
#include "vector/wisp.hpp"

using namespace wisp;
using Eigen::Vector3d;

namespace {

// The curly presets: strands whose curvature radius drops well under the wisp's half-width.
std::vector<sim::ProjectedStrand> curly_presets() {
  std::vector<sim::ProjectedStrand> s;
  // Tight waves: crest radius 2.8 px.
  s.push_back(test::strand_from(0, 40, [](double u) {
    return Vector3d(20 + 200 * u, 100 + 8 * std::sin(2 * M_PI * 200 * u / 30), 2.0);
  }));
  // A ringlet: 300 degrees of a 6 px radius circle.
  s.push_back(test::strand_from(1, 24, [](double u) {
    const double a = 5.2 * u;
    return Vector3d(100 + 6 * std::cos(a), 100 + 6 * std::sin(a), 2.0 + 0.2 * u);
  }));
  // Coils seen from the side, short of looping: helix radius 10 px, pitch 30 px.
  for (double ratio : {0.3, 0.6}) {
    s.push_back(test::strand_from(2, 60, [ratio](double u) {
      const double a = 2 * M_PI * 5 * u, r = 10, pitch = 30, tilt = ratio * pitch / (2 * M_PI * r);
      return Vector3d(30 + 150 * u + tilt * r * std::cos(a), 100 + r * std::sin(a),
                      2.5 + 0.1 * std::cos(a));
    }));
  }
  // An inward spiral whose turns stay 28 px apart.
  s.push_back(test::strand_from(3, 60, [](double u) {
    const double a = 2.5 * M_PI * u, r = 60 - 35 * u;
    return Vector3d(200 + r * std::cos(a), 200 + r * std::sin(a), 2.0);
  }));
  return s;
}

vector::ArrangementStats single(const vector::Wisp& w) {
  vector::ArrangementOptions o;
  o.clip_to_view = false;
  return vector::build_arrangement({w}, o).stats;
}

}  // namespace

TEST_CASE("outlines of the curly presets never cross themselves", "[vector][topology]") {
  vector::WispStyle style;
  style.width = 0.05;  // 10 px half-width at depth 2
  style.profile = vector::WidthProfile::constant();
  vector::WispStyle faraj = style;
  faraj.curvature_clamp = INFINITY;
  int crossed_without_limit = 0;
  for (const auto& strand : curly_presets()) {
    const auto w = vector::build_wisp(strand, 800, style);
    REQUIRE(w);
    const auto st = single(*w);
    INFO("preset strand " << strand.id);
    CHECK(st.faces == 2);
    CHECK(st.intersections == 0);
    const auto loose = vector::build_wisp(strand, 800, faraj);
    crossed_without_limit += single(*loose).intersections > 0;
  }
  CHECK(crossed_without_limit >= 3);  // the test has teeth: Faraj's offsets do loop here
}

TEST_CASE("random wavy and non-looping curly wisps have simple outlines", "[vector][topology]") {
  vector::WispStyle style;
  style.width = 0.05;
  for (const auto& w : vector::build_wisps(test::random_frame(60, 3, 512, 512, false), style)) {
    INFO("strand " << w.strand);
    CHECK(single(w).faces == 2);
  }
}

TEST_CASE("face count equals the exact Bezier arrangement's on small scenes",
          "[vector][topology]") {
  // The exact traits take seconds per scene (CORE algebraic numbers), so the scenes are few:
  // straight and wavy wisps, and one with non-looping coils too.
  vector::WispStyle style;
  style.width = 0.05;
  vector::ArrangementOptions o;
  o.clip_to_view = false;
  struct Scene {
    int count;
    std::uint32_t seed;
    bool coils;
  };
  for (const Scene& scene :
       {Scene{12, 1, false}, Scene{12, 3, false}, Scene{24, 3, false}, Scene{8, 3, true}}) {
    std::vector<vector::Wisp> wisps;
    for (auto& w :
         vector::build_wisps(test::random_frame(scene.count, scene.seed, 512, 512, false), style))
      if (scene.coils || w.strand % 3 != 2) wisps.push_back(std::move(w));
    const auto segments = vector::build_arrangement(wisps, o).stats;
    const auto exact = vector::exact_bezier_topology(wisps);
    INFO(scene.count << " wisps, seed " << scene.seed);
    CHECK(segments.faces == exact.faces);
    CHECK(segments.faces > int(wisps.size()) / 2);  // the scenes do overlap
  }
}
