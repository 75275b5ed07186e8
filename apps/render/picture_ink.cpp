// Variable-width Bezier ink strokes as constant-width pieces (see ink_pieces in frame.hpp).
#include <algorithm>
#include <cmath>

#include "apps/render/picture.hpp"
#include "vector/ink_strokes.hpp"

namespace wisp::render {
namespace {

using Eigen::Vector2d;
using Cubic = std::array<Vector2d, 4>;
using vector::width_at;

// The part [u0, u1] of a cubic (de Casteljau twice).
Cubic sub_cubic(const Cubic& c, double u0, double u1) {
  const auto split_right = [](const Cubic& b, double u) {  // the part [u, 1]
    const Vector2d p01 = b[0] + u * (b[1] - b[0]), p12 = b[1] + u * (b[2] - b[1]),
                   p23 = b[2] + u * (b[3] - b[2]);
    const Vector2d p012 = p01 + u * (p12 - p01), p123 = p12 + u * (p23 - p12);
    const Vector2d m = p012 + u * (p123 - p012);
    return Cubic{m, p123, p23, b[3]};
  };
  const auto split_left = [](const Cubic& b, double u) {  // the part [0, u]
    const Vector2d p01 = b[0] + u * (b[1] - b[0]), p12 = b[1] + u * (b[2] - b[1]),
                   p23 = b[2] + u * (b[3] - b[2]);
    const Vector2d p012 = p01 + u * (p12 - p01), p123 = p12 + u * (p23 - p12);
    const Vector2d m = p012 + u * (p123 - p012);
    return Cubic{b[0], p01, p012, m};
  };
  if (u0 <= 0 && u1 >= 1) return c;
  const Cubic right = u0 > 0 ? split_right(c, u0) : c;
  if (u1 >= 1) return right;
  return split_left(right, (u1 - u0) / (1 - u0));
}

}  // namespace

std::vector<InkPiece> ink_pieces(const InkStroke& stroke, double step) {
  std::vector<InkPiece> out;
  const auto& p = stroke.curve;
  const int k = p.size() >= 4 ? int(p.size() - 1) / 3 : 0;
  if (k == 0 || !(step > 0)) return out;
  const auto level = [&](double s) { return std::lround(width_at(stroke.curve_width, s) / step); };
  long current = -1;
  for (int i = 0; i < k; ++i) {
    const Cubic c{p[3 * i], p[3 * i + 1], p[3 * i + 2], p[3 * i + 3]};
    const double s0 = double(i) / k, s1 = double(i + 1) / k;
    // Enough sub-intervals that the width changes by at most half a step within each, given the
    // width's variation over the cubic (its stops inside and its ends).
    double variation = 0, prev = width_at(stroke.curve_width, s0);
    for (const auto& [s, w] : stroke.curve_width)
      if (s > s0 && s < s1) variation += std::abs(w - prev), prev = w;
    variation += std::abs(width_at(stroke.curve_width, s1) - prev);
    const int m = std::clamp(int(std::ceil(2 * variation / step)), 1, 256);
    // Runs of equal rounded width inside this cubic, found on the m sub-intervals' middles.
    int a = 0;
    while (a < m) {
      const long lv = level(s0 + (a + 0.5) / m * (s1 - s0));
      int b = a + 1;
      while (b < m && level(s0 + (b + 0.5) / m * (s1 - s0)) == lv) ++b;
      const Cubic piece = sub_cubic(c, double(a) / m, double(b) / m);
      if (lv == 0) {
        current = -1;
      } else if (lv == current && !out.empty()) {
        out.back().points.insert(out.back().points.end(), piece.begin() + 1, piece.end());
      } else {
        out.push_back({{piece.begin(), piece.end()}, lv * step});
        current = lv;
      }
      a = b;
    }
  }
  return out;
}

}  // namespace wisp::render
