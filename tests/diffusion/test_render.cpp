// render_drawing: scaling, and the reblur of Orzan et al. (diffused blur values, spatially
// varying Gaussian).
#include <catch2/catch.hpp>
#include <cmath>

#include "diffusion/blur.hpp"
#include "diffusion/render.hpp"

using namespace wisp::diffusion;

namespace {

// A vertical edge at x = 32.0 from top to bottom: black on its right (x > 32, since travelling
// downwards the left side (-d.y, d.x) points to -x), white on its left.
Drawing edge(float sigma) {
  DiffusionCurve c;
  c.points = {{32, -1}, {32, 20}, {32, 44}, {32, 65}};
  c.left = {{0, Color(1, 1, 1)}};
  c.right = {{0, Color(0, 0, 0)}};
  c.blur = {{0, sigma}, {1, sigma}};
  Drawing d;
  d.width = d.height = 64;
  d.curves = {c};
  return d;
}

}  // namespace

TEST_CASE("a curve without blur gives a sharp step", "[render]") {
  RenderStats st;
  const Image im = render_drawing(edge(0), 64, 64, {}, &st);
  CHECK(!st.blurred);
  CHECK(im.planes[32 * 64 + 31] == Approx(1.0f).margin(1e-4));
  CHECK(im.planes[32 * 64 + 32] == Approx(0.0f).margin(1e-4));
}

TEST_CASE("blur values along a curve blur the edge like a Gaussian of that sigma", "[render]") {
  const float sigma = 4;
  RenderStats st;
  const Image im = render_drawing(edge(sigma), 64, 64, {}, &st);
  CHECK(st.blurred);
  // Across the edge the profile is a blurred step: 1 - Phi((x - 32) / sigma).
  for (int x = 20; x < 44; ++x) {
    const double expected = 0.5 * std::erfc((x + 0.5 - 32) / (sigma * std::sqrt(2.0)));
    INFO("x = " << x);
    CHECK(im.planes[32 * 64 + x] == Approx(expected).margin(0.03));
  }
}

TEST_CASE("the blur ladder is exact on its rungs and between them stays between them", "[render]") {
  std::vector<float> img(64 * 64, 0.0f);
  img[32 * 64 + 32] = 1.0f;
  const auto blurred = [&](float s) {
    return spatially_varying_blur(img, 1, 64, 64, std::vector<float>(64 * 64, s));
  };
  const auto a = blurred(2), b = blurred(4), mid = blurred(3);
  CHECK(blurred(0) == img);
  for (int i = 0; i < 64 * 64; ++i) {
    CHECK(mid[i] >= std::min(a[i], b[i]) - 1e-7f);
    CHECK(mid[i] <= std::max(a[i], b[i]) + 1e-7f);
  }
  double sum = 0;
  for (float v : b) sum += v;
  CHECK(sum == Approx(1.0).margin(1e-4));  // blur preserves the total
}

TEST_CASE("drawing coordinates scale to the output size", "[render]") {
  const Image small = render_drawing(edge(0), 32, 32);
  CHECK(small.width == 32);
  CHECK(small.planes[16 * 32 + 15] == Approx(1.0f).margin(1e-4));
  CHECK(small.planes[16 * 32 + 16] == Approx(0.0f).margin(1e-4));
  CHECK_THROWS_AS(render_drawing(Drawing{}, 32, 32), std::invalid_argument);
}

TEST_CASE("a thin feature with Neumann outer sides leaves the colour around it undisturbed",
          "[render]") {
  // Crane's legs and feathers: two open curves from one tip to the other, black between them,
  // Neumann outside, 0 to 2 pixels thick and tapering below a pixel at both ends, in a grey
  // field (two grey lines at the sides). small-usvg lets each pixel's nearest side decide, so
  // outside pixels never see the black of the far side and the grey is undisturbed; with
  // transparent Neumann sides the black would leak out around the tapering ends.
  DiffusionCurve upper, lower;
  upper.points = {{8, 31.2}, {20, 29.8}, {44, 29.8}, {56, 31.2}};
  upper.left = {{0, Color(0, 0, 0)}};  // below it (left of travel in +x, y down): the inside
  upper.right_boundary = Boundary::Neumann;
  lower.points = {{8, 31.2}, {20, 32.4}, {44, 32.4}, {56, 31.2}};
  lower.right = {{0, Color(0, 0, 0)}};  // above it: the inside
  lower.left_boundary = Boundary::Neumann;
  const auto grey_line = [](double x) {
    DiffusionCurve c;
    c.points = {{x, -1}, {x, 20}, {x, 44}, {x, 65}};
    c.left = c.right = {{0, Color(0.5f, 0.5f, 0.5f)}};
    return c;
  };
  Drawing d;
  d.width = d.height = 64;
  d.curves = {grey_line(2), upper, lower, grey_line(62)};
  const Image im = render_drawing(d, 64, 64);
  const size_t n = size_t(64) * 64;
  int checked = 0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      if (x < 3 || x > 60 || std::abs(y + 0.5 - 31) < 3) continue;  // off the lines and feature
      for (int c = 0; c < 3; ++c) CHECK(std::abs(im.planes[c * n + y * 64 + x] - 0.5f) < 2e-3f);
      ++checked;
    }
  CHECK(checked > 2500);
  // The inside still is black.
  CHECK(im.planes[31 * 64 + 32] < 1e-3f);
}

TEST_CASE("an open curve inside a closed loop constrains with both its colours", "[render]") {
  // small-usvg's partition prunes a dangling edge only from the turning number of its loop; the
  // edge stays a boundary curve with both sides, so the curve is not dropped.
  DiffusionCurve ring;
  ring.points = {{4, 32}, {4, 4}, {60, 4}, {60, 32}, {60, 60}, {4, 60}, {4, 32}};
  ring.left = ring.right = {{0, Color(0.5f, 0.5f, 0.5f)}};
  DiffusionCurve open;
  open.points = {{32, 16}, {32, 26}, {32, 38}, {32, 48}};  // downwards: left is -x
  open.left = {{0, Color(1, 0, 0)}};
  open.right = {{0, Color(0, 0, 1)}};
  Drawing d;
  d.width = d.height = 64;
  d.curves = {ring, open};
  const Image im = render_drawing(d, 64, 64);
  const size_t n = size_t(64) * 64, at_left = 32 * 64 + 31, at_right = 32 * 64 + 32;
  CHECK(im.planes[at_left] > 0.9f);  // red just left of it
  CHECK(im.planes[2 * n + at_left] < 0.1f);
  CHECK(im.planes[2 * n + at_right] > 0.9f);  // blue just right of it
  CHECK(im.planes[at_right] < 0.1f);
}

TEST_CASE("pyramid rungs stay within about 2/255 of the exact blur", "[render]") {
  const int n = 96;
  std::vector<float> step(n * n);
  for (int i = 0; i < n * n; ++i) step[i] = (i % n) >= n / 2 ? 1.0f : 0.0f;
  BlurOptions pyramid;
  pyramid.pyramid_from = 4;
  for (const float s : {4.0f, 6.0f, 8.0f, 16.0f}) {
    const std::vector<float> sigma(n * n, s);
    const auto exact = spatially_varying_blur(step, 1, n, n, sigma);
    const auto fast = spatially_varying_blur(step, 1, n, n, sigma, pyramid);
    float worst = 0;
    for (int i = 0; i < n * n; ++i) worst = std::max(worst, std::abs(exact[i] - fast[i]));
    INFO("sigma " << s);
    CHECK(worst < 0.01f);
  }
}

TEST_CASE("the blur map alone diffuses the curves' blur values between them", "[render]") {
  // Vertical lines at x = 16 and 48 with blur 2 and 6: linear in between, constant outside.
  const auto line = [](double x, float sigma) {
    DiffusionCurve c;
    c.points = {{x, -1}, {x, 20}, {x, 44}, {x, 65}};
    c.blur = {{0, sigma}};
    return c;
  };
  const Solution map = solve_blur_map({line(16, 2), line(48, 6)}, 64, 64, {});
  REQUIRE(map.channels == 1);
  for (int x : {4, 20, 32, 40, 60}) {
    const double expected = x < 16 ? 2 : x > 48 ? 6 : 2 + 4 * (x + 0.5 - 16) / 32;
    INFO("x = " << x);
    CHECK(map.planes[32 * 64 + x] == Approx(expected).margin(1e-3));
  }
}
