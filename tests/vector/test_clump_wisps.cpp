// Wisps of a dense groom's clumps (sim/clumps.hpp): a guide that carries its clump's width is
// drawn that wide, and at rest each clump's wisp covers its strands as the camera sees them.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>
#include <limits>

#include "sim/camera.hpp"
#include "sim/clumps.hpp"
#include "vector/wisp.hpp"

using namespace wisp;
using Eigen::Vector2d;
using Eigen::Vector3d;

namespace {

// Nonzero winding of the closed outline polygon around p.
bool inside(const std::vector<vector::OutlineVertex>& poly, const Vector2d& p) {
  int winding = 0;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Vector2d& a = poly[i].p;
    const Vector2d& b = poly[(i + 1) % poly.size()].p;
    const double side = (b.x() - a.x()) * (p.y() - a.y()) - (p.x() - a.x()) * (b.y() - a.y());
    if (a.y() <= p.y()) {
      if (b.y() > p.y() && side > 0) ++winding;
    } else if (b.y() <= p.y() && side < 0) {
      --winding;
    }
  }
  return winding != 0;
}

}  // namespace

TEST_CASE("a strand that carries a clump width is drawn that wide, untapered, square-capped",
          "[vector][clumps]") {
  sim::ProjectedStrand s;
  for (int i = 0; i <= 10; ++i) {
    s.pixel.emplace_back(100, 10 + 20 * i);
    s.depth.push_back(2.0);
    s.width.push_back(0.01 + 0.002 * i);
  }
  vector::WispStyle style;
  style.width = 0.5;  // the style's width is not used
  const std::optional<vector::Wisp> w = vector::build_wisp(s, 400, style);
  REQUIRE(w);
  // Eleven samples and a cap point past each end, as wide as the end.
  REQUIRE(w->half_width_left.size() == 13);
  for (int i = 0; i < 13; ++i) {
    const double expected = 0.5 * s.width[std::clamp(i - 1, 0, 10)] * 400 / 2.0;
    CHECK(w->half_width_left[i] == Approx(expected));
    CHECK(w->half_width_right[i] == Approx(expected));
  }
  const double root_half = 0.5 * 0.01 * 400 / 2.0, tip_half = 0.5 * 0.03 * 400 / 2.0;
  CHECK(w->bounds.min().y() == Approx(10 - root_half));
  CHECK(w->bounds.max().y() == Approx(210 + tip_half));
  s.width.pop_back();
  CHECK_THROWS_WITH(vector::build_wisp(s, 400, style), Catch::Contains("width has 10 entries"));
}

TEST_CASE("at rest, each clump's wisp covers 95 % of its strands' projected samples",
          "[vector][clumps]") {
  sim::HairParams hair;
  hair.count = 20000;
  hair.segments = 29;
  const sim::HeadGeometry head;
  const std::vector<sim::Polyline> groom = sim::generate_hair(hair, sim::HeadShape(head));
  sim::ClumpOptions options;
  options.count = 150;
  const sim::Clumps clumps = sim::cluster_strands(groom, options);
  std::vector<std::vector<int>> members(clumps.guide.size());
  for (std::size_t i = 0; i < groom.size(); ++i) members[clumps.clump_of[i]].push_back(int(i));

  sim::StrandFrame rest;
  sim::ProjectorOptions projection;
  for (std::size_t c = 0; c < clumps.guide.size(); ++c) {
    rest.strands.push_back(sim::resample(groom[clumps.guide[c]], 24));
    projection.widths.push_back(sim::clump_width(rest.strands.back(), groom, members[c]));
  }
  // The default scene's three-quarter view and a view from behind: the samples the camera sees
  // against the whole wisp, for the clumps whose guide the camera sees (where the head hides the
  // guide but not all its strands, a renderer of guides shows nothing of the clump, whatever its
  // width). Each clump is covered by its wisp as wide as the clump; the style's curvature clamp
  // then narrows the inner side of tight bends, which leaves some strands out there.
  for (const bool clamp : {false, true}) {
    vector::WispStyle style;
    style.trim_hidden = false;
    if (!clamp) style.curvature_clamp = std::numeric_limits<double>::infinity();
    for (const Vector3d& eye : {Vector3d(0.68, 0.04, 0.86), Vector3d(0.1, 0.2, -1.1)}) {
      sim::CameraParams camera;
      camera.eye = eye;
      camera.width = camera.height = 512;
      sim::Projector projector(head, camera, projection);
      const sim::ProjectedFrame frame = projector.project(rest);
      sim::StrandFrame all;
      all.strands = groom;
      const sim::ProjectedFrame seen = sim::Projector(head, camera).project(all);
      double worst = 1;
      int clumps_seen = 0, in_all = 0, total_all = 0;
      for (std::size_t c = 0; c < clumps.guide.size(); ++c) {
        const std::vector<std::uint8_t>& shown = frame.strands[c].visible;
        if (std::count(shown.begin(), shown.end(), 1) < 0.8 * shown.size()) continue;
        const std::optional<vector::Wisp> w =
            vector::build_wisp(frame.strands[c], frame.focal_px, style);
        REQUIRE(w);
        const std::vector<vector::OutlineVertex> poly = vector::outline_polygon(*w);
        int in = 0, total = 0;
        for (int m : members[c])
          for (std::size_t i = 0; i < groom[m].size(); ++i)
            if (seen.strands[m].visible[i]) {
              in += inside(poly, seen.strands[m].pixel[i]);
              ++total;
            }
        if (total < 100) continue;  // a clump the camera hardly sees
        ++clumps_seen;
        in_all += in;
        total_all += total;
        worst = std::min(worst, double(in) / total);
        INFO("clump " << c << " of " << members[c].size() << " strands, " << total
                      << " samples seen");
        if (!clamp) CHECK(double(in) / total >= 0.95);
      }
      std::printf(
          "[measured] eye (%.2f, %.2f, %.2f), curvature clamp %s: %d clumps seen, the "
          "least covered %.3f, all together %.3f\n",
          eye.x(), eye.y(), eye.z(), clamp ? "0.8" : "off", clumps_seen, worst,
          double(in_all) / total_all);
      CHECK(clumps_seen > 50);
      CHECK(double(in_all) / total_all >= 0.95);
    }
  }
}
