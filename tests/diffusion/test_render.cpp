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
