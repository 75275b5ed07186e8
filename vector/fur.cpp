// Fur tufts as filled paths (see fur.hpp).
#include "vector/fur.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "vector/hair_shading.hpp"
#include "vector/hair_style.hpp"

namespace wisp::vector {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

Vector2d left_normal(const Vector2d& d) {
  const double n = d.norm();
  return n > 1e-12 ? Vector2d(d.y() / n, -d.x() / n) : Vector2d(0, 0);
}

// A strand from its quadratic (root q0, control q1, tip q2) with half-width h at the root: up
// the left side as the quadratic's cubic with its controls offset by 2h/3 and h/3 (the width
// falls linearly to the tip), down the right side likewise, and straight across the root.
std::vector<Vector2d> strand_loop(const Vector2d& q0, const Vector2d& q1, const Vector2d& q2,
                                  double h) {
  const Vector2d c1 = q0 + 2.0 / 3 * (q1 - q0), c2 = q2 + 2.0 / 3 * (q1 - q2);
  Vector2d d0 = q1 - q0, d2 = q2 - q1;
  if (d0.norm() < 1e-9) d0 = q2 - q0;
  if (d2.norm() < 1e-9) d2 = q2 - q0;
  const Vector2d n0 = left_normal(d0), n2 = left_normal(d2);
  const Vector2d a = q0 + h * n0, b = q0 - h * n0;
  return {a,  c1 + 2.0 / 3 * h * n0, c2 + 1.0 / 3 * h * n2,
          q2, c2 - 1.0 / 3 * h * n2, c1 - 2.0 / 3 * h * n0,
          b,  b + (a - b) / 3,       b + 2.0 * (a - b) / 3,
          a};
}

}  // namespace

void validate(const FurStyle& f) {
  using sim::require;
  require(f.strand_width > 0 && f.strand_width <= 0.1, "strand_width", "must be in (0, 0.1] m");
  require(f.fin_band > 0 && f.fin_band <= 1, "fin_band", "must be in (0, 1] (|N.V|)");
  require(f.interior_opacity >= 0 && f.interior_opacity <= 1, "interior_opacity",
          "must be in [0, 1]");
  require(f.max_opacity > 0 && f.max_opacity <= 1, "max_opacity", "must be in (0, 1]");
  require(f.min_width_px >= 0 && f.min_width_px <= 100, "min_width_px", "must be in [0, 100] px");
}

double fin_opacity(double facing, const FurStyle& f) {
  double a = std::clamp(1 - std::abs(facing) / f.fin_band, 0.0, 1.0);
  if (facing > 0) a = std::max(a, f.interior_opacity);
  return a * f.max_opacity;
}

double fur_intensity(const Vector3d& T, const Vector3d& N, const Vector3d& L,
                     const HairStyle& style) {
  const Lighting& m = style.shading.lighting;
  const double lit =
      m.ambient + head_shadow(N, L, m) * (m.kajiya_diffuse * kajiya_kay_diffuse(T, L) +
                                          m.lambert * std::max(0.0, N.dot(L)));
  return std::clamp(lit / std::max(1e-9, max_intensity(m)), 0.0, 1.0);
}

Eigen::Vector3f coat_color(const Vector3d& T, const Vector3d& N, const Vector3d& L,
                           const HairStyle& style) {
  const double k = std::clamp(2 * style.base.tone * fur_intensity(T, N, L, style), 0.0, 1.0);
  return style.shadow + float(k) * (style.hair - style.shadow);
}

std::vector<FurTuft> fur_tufts(const sim::ProjectedFur& fur, const HairStyle& style) {
  const FurStyle& fs = style.fur;
  const Lighting& m = style.shading.lighting;
  const Vector3d L = fur.light_dir;
  std::vector<int> order(fur.tufts.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    const double da = fur.tufts[a].depth, db = fur.tufts[b].depth;
    return da != db ? da > db : fur.tufts[a].id < fur.tufts[b].id;
  });
  std::vector<FurTuft> out;
  out.reserve(order.size());
  for (int i : order) {
    const sim::ProjectedTuft& t = fur.tufts[i];
    const double opacity = fin_opacity(t.facing, fs);
    if (opacity < 1.0 / 255) continue;
    FurTuft tuft;
    tuft.id = t.id;
    tuft.opacity = float(opacity);
    const Vector3d V = (fur.eye - t.root).normalized();
    const double tone = fur_intensity(t.tangent, t.normal, L, style);
    const double spec = m.specular * head_shadow(t.normal, L, m) *
                        kajiya_kay_specular(t.tangent, L, V, m.shininess);
    const float variance = float(t.variance);
    tuft.color = ((style.shadow + float(tone) * (style.hair - style.shadow)) * variance +
                  float(spec) * style.highlight)
                     .cwiseMax(0.0f)
                     .cwiseMin(1.0f);
    const size_t strands = t.strand_depth.size();
    tuft.root = strands ? t.strand_points[0] : Vector2d::Zero();
    for (size_t s = 0; s < strands; ++s) {
      const Vector2d q0 = t.strand_points[3 * s], q1 = t.strand_points[3 * s + 1],
                     q2 = t.strand_points[3 * s + 2];
      if ((q2 - q0).norm() < 0.5) continue;  // seen end-on: nothing to draw
      const double h =
          0.5 * std::max(fs.min_width_px, fs.strand_width * fur.focal_px / t.strand_depth[s]);
      tuft.loops.push_back(strand_loop(q0, q1, q2, h));
    }
    if (!tuft.loops.empty()) out.push_back(std::move(tuft));
  }
  return out;
}

}  // namespace wisp::vector
