// antialias: pixels that sharp curves cross mix both sides' solved colours by the area each side
// covers, colours never cross a curve, pixels no curve crosses keep their solved value, and a
// region leaves the outside out.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>

#include "diffusion/antialias.hpp"
#include "diffusion/render.hpp"

using namespace wisp::diffusion;
using Eigen::Vector2d;

namespace {

// A straight curve from a to b (evenly spaced control points) with one colour per side.
DiffusionCurve line(Vector2d a, Vector2d b, Color left, Color right) {
  DiffusionCurve c;
  for (int k = 0; k <= 3; ++k) c.points.push_back(a + (b - a) * (k / 3.0));
  c.left = {{0, left}};
  c.right = {{0, right}};
  return c;
}

Drawing drawing(int size, std::vector<DiffusionCurve> curves) {
  Drawing d;
  d.width = d.height = size;
  d.curves = std::move(curves);
  return d;
}

float red(const Image& im, int x, int y) {
  return im.planes[size_t(y) * im.width + x];
}

const Color kWhite(1, 1, 1), kBlack(0, 0, 0);

}  // namespace

TEST_CASE("a pixel a straight edge crosses takes each side's colour by the area it covers",
          "[antialias]") {
  // Travelling down, the left side (-d.y, d.x) points to -x: white left of x = 10.25.
  const Drawing d = drawing(32, {line({10.25, -1}, {10.25, 33}, kWhite, kBlack)});
  const Image sharp = render_drawing(d, 32, 32, {}, nullptr, false);
  RenderStats st;
  const Image im = render_drawing(d, 32, 32, {}, &st, true);
  CHECK(st.antialiased_pixels == 32);  // one column
  for (int y = 0; y < 32; ++y) {
    CHECK(red(sharp, 10, y) == Approx(0).margin(1e-4));  // the centre 10.5 is on the black side
    CHECK(red(im, 10, y) == Approx(0.25).margin(1e-4));  // a quarter of the pixel is white
    for (int x : {0, 9, 11, 31}) CHECK(red(im, x, y) == red(sharp, x, y));
  }
}

TEST_CASE("along a slanted edge every pixel's mix is its covered area", "[antialias]") {
  // y = 0.3 x + 5: white below it (travelling +x, the left side (-d.y, d.x) points to +y).
  const Vector2d a(-1, 5 - 0.3), b(65, 5 + 0.3 * 65);
  const Drawing d = drawing(64, {line(a, b, kWhite, kBlack)});
  const Image im = render_drawing(d, 64, 64, {}, nullptr, true);
  for (int x = 0; x < 64; ++x)
    for (int y = 0; y < 64; ++y) {
      // Exact white area of the pixel: the part below the line, column by column.
      double area = 0;
      const int kCols = 400;
      for (int k = 0; k < kCols; ++k) {
        const double line_y = 5 + 0.3 * (x + (k + 0.5) / kCols);
        area += std::clamp(y + 1 - line_y, 0.0, 1.0) / kCols;
      }
      // 4 x 4 sub-samples resolve the area to within a row of them plus the slope's share.
      INFO("pixel " << x << "," << y);
      CHECK(red(im, x, y) == Approx(area).margin(0.3 / 4 + 1e-3));
    }
}

TEST_CASE("colour does not leak across a curve into a thin feature", "[antialias]") {
  // A white band 0.6 px wide between two curves holds no pixel centre; outside it is black.
  // Each crossed pixel shows white in proportion to the band's area in it, never more.
  const Drawing d = drawing(
      16, {line({7.2, -1}, {7.2, 17}, kBlack, kWhite), line({7.8, -1}, {7.8, 17}, kWhite, kBlack)});
  const Image im = render_drawing(d, 16, 16, {}, nullptr, true);
  for (int y = 0; y < 16; ++y) {
    CHECK(red(im, 7, y) == Approx(0.5).margin(1e-4));  // sub-samples 7.375 and 7.625 are white
    CHECK(red(im, 6, y) == Approx(0).margin(1e-4));
    CHECK(red(im, 8, y) == Approx(0).margin(1e-4));
  }
}

TEST_CASE("sub-samples outside the region do not count", "[antialias]") {
  const Drawing d = drawing(32, {line({10.25, -1}, {10.25, 33}, kWhite, kBlack)});
  Image im = render_drawing(d, 32, 32, {}, nullptr, false);
  AntialiasRegion region;  // the black side alone is shown: x >= 10.25
  region.rings = {{{10.25, -1}, {33, -1}, {33, 33}, {10.25, 33}}};
  region.centres.assign(32 * 32, 1);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x <= 9; ++x) region.centres[y * 32 + x] = 0;
  const AntialiasStats st = antialias(d.curves, 32, 32, im.planes, &region);
  CHECK(st.pixels == 32);
  for (int y = 0; y < 32; ++y) CHECK(red(im, 10, y) == Approx(0).margin(1e-4));  // black alone
}

TEST_CASE("a region thinner than a pixel shows its own colour, not the solve's outside it",
          "[antialias]") {
  // A white strand 0.6 px wide (black outside its outline) holds no pixel centre. Shown through
  // a mask of the strand alone, its pixels must carry the strand's colour: the mask supplies the
  // coverage. The solved values at their centres are the outside's black.
  const Drawing d = drawing(
      16, {line({7.6, -1}, {7.6, 17}, kBlack, kWhite), line({8.2, -1}, {8.2, 17}, kWhite, kBlack)});
  Image im = render_drawing(d, 16, 16, {}, nullptr, false);
  REQUIRE(red(im, 7, 8) < 0.5);
  REQUIRE(red(im, 8, 8) < 0.5);
  AntialiasRegion region;
  region.rings = {{{7.6, -1}, {8.2, -1}, {8.2, 17}, {7.6, 17}}};
  region.centres.assign(16 * 16, 0);
  antialias(d.curves, 16, 16, im.planes, &region);
  for (int y = 0; y < 16; ++y) {
    CHECK(red(im, 7, y) == Approx(1).margin(1e-4));
    CHECK(red(im, 8, y) == Approx(1).margin(1e-4));
  }
}

TEST_CASE("hidden parts of a curve do not anti-alias", "[antialias]") {
  DiffusionCurve c = line({10.25, -1}, {10.25, 33}, kWhite, kBlack);
  c.active = {{0.0, 0.5}};  // the upper half only: y < 16
  const Drawing d = drawing(32, {c});
  const Image sharp = render_drawing(d, 32, 32, {}, nullptr, false);
  const Image im = render_drawing(d, 32, 32, {}, nullptr, true);
  // A quarter of the pixel is on the white side (not quite white near the curve's end, where
  // colour flows round it): the mix lies between the two sides' solved values, a quarter of the
  // way, to within the solved values' slope over the sub-samples' distance from the curve.
  const float white_side = red(sharp, 9, 4), black_side = red(sharp, 10, 4);
  CHECK(red(im, 10, 4) == Approx(0.25 * white_side + 0.75 * black_side).margin(0.01));
  CHECK(red(sharp, 9, 4) - red(sharp, 10, 4) > 0.9);
  CHECK(red(im, 10, 28) == red(sharp, 10, 28));  // no curve there: left as solved
}

TEST_CASE("a source of the solve's window alone gives the whole image's pixels", "[antialias]") {
  // A slanted edge in the middle of a 32^2 image; the solve's colours kept for a window around
  // it only (as the renderer keeps them) stand for 0 outside it.
  const Drawing d = drawing(32, {line({12.3, -1}, {17.6, 33}, kWhite, kBlack)});
  const Image sharp = render_drawing(d, 32, 32, {}, nullptr, false);
  std::vector<float> whole = sharp.planes;
  const AntialiasStats st = antialias(d.curves, 32, 32, whole);
  const auto window_of = [](const std::vector<float>& from, const PixelWindow& w) {
    std::vector<float> planes(3 * w.pixel_count());
    for (int c = 0; c < 3; ++c)
      for (int y = 0; y < w.height; ++y)
        for (int x = 0; x < w.width; ++x)
          planes[c * w.pixel_count() + size_t(y) * w.width + x] =
              from[c * 32 * 32 + size_t(w.y + y) * 32 + w.x + x];
    return planes;
  };
  const auto window_source = [&](const PixelWindow& w) { return window_of(sharp.planes, w); };
  // The edge's pixels and their neighbours lie in columns 10-19: a window of them is enough.
  const PixelWindow around{8, 0, 14, 32}, image{0, 0, 32, 32};
  std::vector<float> windowed = sharp.planes;
  CHECK(antialias(d.curves, 32, 32, window_source(around), around, windowed, image).pixels ==
        st.pixels);
  CHECK(windowed == whole);
  // Written into planes of the window alone (as the renderer keeps its picture): the same pixels.
  std::vector<float> window_only = window_source(around);
  antialias(d.curves, 32, 32, window_source(around), around, window_only, around);
  CHECK(window_only == window_of(whole, around));
  CHECK(window_only != window_source(around));
  // A window that leaves out the white side's centres reads 0 there: the edge's pixels change.
  const PixelWindow right_of_edge{16, 0, 16, 32};
  std::vector<float> cut = sharp.planes;
  antialias(d.curves, 32, 32, window_source(right_of_edge), right_of_edge, cut, image);
  float largest = 0;
  for (size_t i = 0; i < cut.size(); ++i) largest = std::max(largest, std::abs(cut[i] - whole[i]));
  CHECK(largest > 0.3f);
  // A window reaching outside the image is refused.
  CHECK_THROWS_AS(antialias(d.curves, 32, 32, window_source(around), PixelWindow{20, 0, 14, 32},
                            windowed, image),
                  std::invalid_argument);
  CHECK_THROWS_AS(antialias(d.curves, 32, 32, window_source(around), around, window_only,
                            PixelWindow{20, 0, 14, 32}),
                  std::invalid_argument);
}

TEST_CASE("antialias refuses mismatched sizes", "[antialias]") {
  std::vector<float> planes(3 * 4 * 4, 0.0f);
  CHECK_THROWS_AS(antialias({}, 5, 4, planes), std::invalid_argument);
  AntialiasRegion region;
  region.centres.assign(3, 1);
  CHECK_THROWS_AS(antialias({}, 4, 4, planes, &region), std::invalid_argument);
  AntialiasOptions o;
  o.samples = 0;
  CHECK_THROWS_AS(antialias({}, 4, 4, planes, nullptr, o), std::invalid_argument);
}
