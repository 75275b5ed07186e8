// The arrangement against the independent raster reference on seeded random scenes of straight,
// wavy and curly wisps: the front-most wisp per covered pixel and the hair mask.
#include <catch2/catch.hpp>

#include "tests/vector/debug_png.hpp"
#include "tests/vector/raster_reference.hpp"
#include "tests/vector/scenes.hpp"
#include "vector/arrangement.hpp"
#include "vector/wisp.hpp"

using namespace wisp;

namespace {

struct Agreement {
  double front = 0;    // fraction of reference-covered pixels with the same front-most wisp
  double iou = 0;      // mask versus the raster union
  double outline = 0;  // fraction of outline sample points with the same visibility
  int covered = 0;
};

// Visibility of the midpoint of every outline polygon edge inside the image, decided point by
// point (no other wisp covers it from nearer, no other pass of its own wisp either), compared
// with the arrangement's visible intervals.
double outline_agreement(const std::vector<vector::Wisp>& wisps, const vector::WispArrangement& arr,
                         int size) {
  std::vector<std::vector<Eigen::Vector2d>> rings;
  for (const auto& w : wisps) {
    rings.emplace_back();
    for (const auto& v : vector::outline_polygon(w)) rings.back().push_back(v.p);
  }
  long total = 0, same = 0;
  for (size_t w = 0; w < wisps.size(); ++w) {
    const auto poly = vector::outline_polygon(wisps[w]);
    for (size_t k = 0; k < poly.size(); ++k) {
      const auto &a = poly[k], &b = poly[(k + 1) % poly.size()];
      const Eigen::Vector2d q = 0.5 * (a.p + b.p);
      if (q.minCoeff() < 0.5 || q.maxCoeff() > size - 0.5) continue;
      const double s = 0.5 * (a.s + (k + 1 < poly.size() ? b.s : 1.0)),
                   z = 0.5 * (a.depth + b.depth);
      bool visible = true;
      for (size_t v = 0; v < wisps.size() && visible; ++v) {
        if (v == w || !wisps[v].bounds.contains(q)) continue;
        if (test::winding_number(rings[v], q) != 0 && test::reference_depth(wisps[v], q) < z)
          visible = false;
      }
      if (visible && test::reference_depth(wisps[w], q, 1e-6) < z * (1 - 1e-9)) visible = false;
      bool listed = false;
      for (auto [s0, s1] : arr.visible[w]) listed |= s >= s0 && s <= s1;
      ++total;
      same += listed == visible;
    }
  }
  return double(same) / total;
}

Agreement compare(int count, std::uint32_t seed) {
  const int size = 512;
  const auto frame = test::random_frame(count, seed, size, size);
  vector::WispStyle style;
  style.width = 0.05;
  const auto wisps = vector::build_wisps(frame, style);
  vector::ArrangementOptions options;
  options.view = vector::image_rect(size, size);
  options.keep_faces = true;
  const auto arr = vector::build_arrangement(wisps, options);

  const test::Raster ref = test::reference_front(wisps, size, size);
  const test::Raster got = test::arrangement_front(arr.view, size, size);
  const test::Raster mask = test::mask_raster(arr.mask, size, size);
  long covered = 0, same = 0, inter = 0, uni = 0;
  for (size_t i = 0; i < ref.label.size(); ++i) {
    const bool r = ref.label[i] >= 0, m = mask.label[i] != 0;
    covered += r;
    same += r && ref.label[i] == got.label[i];
    inter += r && m;
    uni += r || m;
  }
  if (const auto dir = test::debug_png_dir(); !dir.empty()) {
    const std::string stem = dir + "/agree_" + std::to_string(count) + "_" + std::to_string(seed);
    test::write_arrangement_png(stem + "_arr.png", arr.view, size, size);
    test::write_raster_png(stem + "_ref.png", ref);
    test::write_diff_png(stem + "_diff.png", ref, got);
  }
  return {double(same) / covered, double(inter) / uni, outline_agreement(wisps, arr, size),
          int(covered)};
}

}  // namespace

TEST_CASE("front-most wisp and hair mask agree with the raster reference", "[vector][raster]") {
  const int count = GENERATE(50, 150, 300);
  for (std::uint32_t seed : {1u, 2u}) {
    const Agreement a = compare(count, seed);
    INFO("wisps " << count << " seed " << seed << ": front agreement " << a.front << ", IoU "
                  << a.iou << " over " << a.covered << " px, outline visibility " << a.outline);
    CHECK(a.covered > 10000);
    CHECK(a.front >= 0.9995);
    CHECK(a.iou >= 0.999);
    CHECK(a.outline >= 0.999);
    if (!test::debug_png_dir().empty())
      WARN("wisps " << count << " seed " << seed << ": front " << a.front << ", IoU " << a.iou
                    << ", outline " << a.outline);
  }
}

TEST_CASE("the arrangement is deterministic", "[vector][raster]") {
  vector::WispStyle style;
  style.width = 0.05;
  const auto wisps = vector::build_wisps(test::random_frame(80, 5), style);
  vector::ArrangementOptions options;
  options.view = vector::image_rect(512, 512);
  options.keep_faces = true;
  const auto a = vector::build_arrangement(wisps, options);
  const auto b = vector::build_arrangement(wisps, options);
  CHECK(a.visible == b.visible);
  REQUIRE(a.mask.polygons.size() == b.mask.polygons.size());
  for (size_t i = 0; i < a.mask.polygons.size(); ++i)
    CHECK(a.mask.polygons[i].outer == b.mask.polygons[i].outer);
  REQUIRE(a.view.faces.size() == b.view.faces.size());
  for (size_t i = 0; i < a.view.faces.size(); ++i) {
    CHECK(a.view.faces[i].cover == b.view.faces[i].cover);
    CHECK(a.view.faces[i].front == b.view.faces[i].front);
  }
  CHECK(a.silhouette.size() == b.silhouette.size());
  CHECK(a.occlusion.size() == b.occlusion.size());
}
