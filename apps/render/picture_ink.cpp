// Variable-width Bezier ink strokes: made from fitted paths, drawn as constant-width pieces (see
// ink_stroke and ink_pieces in picture.hpp).
#include <algorithm>
#include <cmath>

#include "apps/render/picture.hpp"
#include "vector/ink_strokes.hpp"

namespace wisp::render {

InkStroke ink_stroke(const diffusion::BezierPath& c,
                     const std::vector<std::pair<double, double>>& width, const Rgb& color) {
  InkStroke s;
  s.color = color;
  s.closed = c.closed();
  s.curve.points = c.points;
  s.curve_width = width;
  const int k = c.piece_count();
  for (int i = 0; i < k; ++i) {
    const diffusion::Cubic q = c.piece(i);
    for (int j = 0; j < 3; ++j) {
      const double u = j / 3.0, sp = (i + u) / k;
      s.points.push_back(diffusion::eval(q, u));
      s.width.push_back(vector::width_at(width, sp));
    }
  }
  if (!s.closed) {
    s.points.push_back(c.points.back());
    s.width.push_back(vector::width_at(width, 1.0));
  }
  return s;
}

std::vector<InkPiece> ink_pieces(const InkStroke& stroke, double step) {
  using vector::width_at;
  std::vector<InkPiece> out;
  const int k = stroke.curve.piece_count();
  if (k == 0 || !(step > 0)) return out;
  const auto level = [&](double s) { return std::lround(width_at(stroke.curve_width, s) / step); };
  long current = -1;
  for (int i = 0; i < k; ++i) {
    const diffusion::Cubic c = stroke.curve.piece(i);
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
      const diffusion::Cubic piece = diffusion::sub_cubic(c, double(a) / m, double(b) / m);
      if (lv == 0) {
        current = -1;
      } else if (lv == current && !out.empty()) {
        out.back().append(piece);
      } else {
        out.emplace_back().width = lv * step;
        out.back().append(piece);
        current = lv;
      }
      a = b;
    }
  }
  return out;
}

}  // namespace wisp::render
