// Faraj's colouring of wisps as diffusion curves (see hair_curves.hpp).
#include "vector/hair_curves.hpp"

#include <algorithm>

namespace wisp::vector {

double outline_parameter(const Wisp& wisp, double t, bool left_side) {
  const Outline& o = wisp.outline;
  const int k = o.cubic_count();
  const Side wanted = left_side ? Side::Left : Side::Right;
  // Along a side the centre parameter is monotonic: increasing on the left, decreasing on the
  // right. Find the cubic whose end points bracket t and interpolate linearly between them.
  double best_s = -1, best_gap = 1e18;
  for (int i = 0; i < k; ++i) {
    if (o.side[i] != wanted) continue;
    const double t0 = o.t[3 * i], t1 = o.t[3 * i + 3];
    const double lo = std::min(t0, t1), hi = std::max(t0, t1);
    if (t >= lo && t <= hi) {
      const double f = hi > lo ? (t - t0) / (t1 - t0) : 0.0;
      return (i + f) / k;
    }
    const double gap = std::min(std::abs(t - t0), std::abs(t - t1));
    if (gap < best_gap) {
      best_gap = gap;
      best_s = (std::abs(t - t0) < std::abs(t - t1) ? i : i + 1) / double(k);
    }
  }
  return std::clamp(best_s, 0.0, 1.0);
}

std::vector<diffusion::DiffusionCurve> hair_curves(
    const std::vector<Wisp>& wisps,
    const std::vector<std::vector<std::pair<double, double>>>& visible, const HairStyle& style) {
  using diffusion::ColorStop;
  std::vector<diffusion::DiffusionCurve> out;
  out.reserve(wisps.size());
  for (size_t w = 0; w < wisps.size(); ++w) {
    // A wholly hidden wisp constrains nothing (an empty active set would mean "everywhere").
    if (w >= visible.size() || visible[w].empty()) continue;
    const Wisp& wisp = wisps[w];
    diffusion::DiffusionCurve c;
    c.points = wisp.outline.points;
    // Faraj's colour point: the highlight colour at one place along one side, fading back to
    // the hair colour on both sides of it.
    const bool left = style.highlight_on_left;
    const double a = style.highlight_along, h = 0.5 * style.highlight_spread;
    double s[3] = {outline_parameter(wisp, std::clamp(a - h, 0.0, 1.0), left),
                   outline_parameter(wisp, a, left),
                   outline_parameter(wisp, std::clamp(a + h, 0.0, 1.0), left)};
    std::sort(s, s + 3);
    c.left = {{0.0, style.hair},
              {s[0], style.hair},
              {s[1], style.highlight},
              {s[2], style.hair},
              {1.0, style.hair}};
    c.right = {{0.0, style.shadow}, {1.0, style.shadow}};
    c.active = visible[w];
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace wisp::vector
