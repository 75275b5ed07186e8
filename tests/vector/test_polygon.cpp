// The polygon helpers (vector/polygon.hpp): fill_centres, which walks each row's edges only,
// against the plain rule it stands for (every edge of every ring tested at every row), to the
// pixel, on random rings with holes, rings reaching past the image, and vertices on row centres.
#include <catch2/catch.hpp>

#include <random>

#include "vector/polygon.hpp"

using Eigen::Vector2d;
using Rings = std::vector<std::vector<Vector2d>>;

namespace {

// The rule, written plainly: per row, the crossings of every ring edge with the row's centre line,
// sorted; the pixels whose centres lie in [x0, x1) of each pair.
std::vector<std::uint8_t> plain_fill(int width, int height, const Rings& rings) {
  std::vector<std::uint8_t> out(size_t(width) * height, 0);
  for (int y = 0; y < height; ++y) {
    const double yc = y + 0.5;
    std::vector<double> xs;
    for (const auto& r : rings)
      for (size_t i = 0, j = r.size() - 1; i < r.size(); j = i++)
        if ((r[i].y() > yc) != (r[j].y() > yc))
          xs.push_back(r[j].x() + (yc - r[j].y()) * (r[i].x() - r[j].x()) / (r[i].y() - r[j].y()));
    std::sort(xs.begin(), xs.end());
    for (size_t k = 0; k + 1 < xs.size(); k += 2)
      for (int x = std::max(0, int(std::ceil(xs[k] - 0.5)));
           x < std::min(width, int(std::ceil(xs[k + 1] - 0.5))); ++x)
        out[size_t(y) * width + x] = 1;
  }
  return out;
}

}  // namespace

TEST_CASE("fill_centres fills the pixels whose centres the rings hold, as the plain rule does",
          "[vector][polygon]") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coord(-20, 100), radius(2, 40);
  std::uniform_int_distribution<int> corners(3, 40), half(-40, 200);
  constexpr int kWidth = 80, kHeight = 64;
  int filled = 0;
  for (int trial = 0; trial < 200; ++trial) {
    Rings rings;
    const int count = 1 + trial % 4;
    for (int k = 0; k < count; ++k) {
      // A star-shaped ring around a random centre; every fifth vertex on a row's centre or a
      // pixel's edge, where the crossing rule decides ties.
      const Vector2d c(coord(rng), coord(rng));
      const int n = corners(rng);
      std::vector<Vector2d> ring;
      for (int i = 0; i < n; ++i) {
        const double a = 2 * M_PI * i / n;
        Vector2d p = c + radius(rng) * Vector2d(std::cos(a), std::sin(a));
        if (i % 5 == 0) p.y() = 0.5 * half(rng);
        ring.push_back(p);
      }
      rings.push_back(ring);
    }
    std::vector<std::uint8_t> fast(size_t(kWidth) * kHeight, 0);
    wisp::vector::fill_centres(fast, kWidth, kHeight, rings, std::uint8_t(1));
    const std::vector<std::uint8_t> plain = plain_fill(kWidth, kHeight, rings);
    CHECK(fast == plain);
    for (std::uint8_t v : fast) filled += v;
  }
  CHECK(filled > 100000);  // the rings cover a good part of the image, not nothing
}
