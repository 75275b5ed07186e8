// (t, u) coordinates of a wisp (see wisp_chart.hpp).
#include "vector/wisp_chart.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace wisp::vector {

using Eigen::Vector2d;
using Eigen::Vector3d;

WispChart::WispChart(const Wisp& wisp, const sim::ProjectedStrand& strand, const Vector3d& eye)
    : wisp_(wisp), strand_(strand), eye_(eye) {
  if (strand.world.size() != strand.pixel.size() || strand.world.empty())
    throw std::invalid_argument("strand " + std::to_string(strand.id) +
                                ": lit shading needs the 3D position of every sample");
  if (wisp.sections.size() < 2) throw std::invalid_argument("wisp without sections");
  t0_ = wisp.sections.front().t;
  t1_ = wisp.sections.back().t;
}

int WispChart::section_before(double t) const {
  const auto& s = wisp_.sections;
  const auto it = std::upper_bound(s.begin(), s.end(), t,
                                   [](double v, const Section& sec) { return v < sec.t; });
  return std::clamp(int(it - s.begin()) - 1, 0, int(s.size()) - 2);
}

Vector2d WispChart::point(double t, double u) const {
  const auto& s = wisp_.sections;
  const int i = section_before(t);
  const Section &a = s[i], &b = s[i + 1];
  const double f = b.t > a.t ? std::clamp((t - a.t) / (b.t - a.t), 0.0, 1.0) : 0.0;
  const Vector2d c = (1 - f) * a.centre + f * b.centre;
  const Vector2d side =
      u >= 0 ? Vector2d((1 - f) * a.left + f * b.left) : Vector2d((1 - f) * a.right + f * b.right);
  return c + std::min(std::abs(u), 1.0) * (side - c);
}

double WispChart::control_index(double t) const {
  const int n = int(wisp_.centre.points.size());
  return std::clamp(t, 0.0, 1.0) * (n - 1);
}

namespace {
template <class T>
T lerp_at(const std::vector<T>& v, double x) {
  const int n = int(v.size());
  const int i = std::clamp(int(std::floor(x)), 0, n - 2);
  const double f = std::clamp(x - i, 0.0, 1.0);
  return (1 - f) * v[i] + f * v[i + 1];
}
}  // namespace

Vector3d WispChart::tangent(double t) const {
  const auto& tan = wisp_.centre.tangent;
  Vector3d v = tan.size() >= 2 ? lerp_at(tan, control_index(t)) : Vector3d::Zero();
  if (v.norm() < 1e-12) {
    // No tangents given: the chord of the strand's samples around t.
    const double x = strand_u(t) * (strand_.world.size() - 1);
    const int i = std::clamp(int(x), 0, int(strand_.world.size()) - 2);
    v = strand_.world.size() >= 2 ? Vector3d(strand_.world[i + 1] - strand_.world[i])
                                  : Vector3d::UnitY();
  }
  return v.norm() > 0 ? Vector3d(v.normalized()) : Vector3d::UnitY();
}

double WispChart::strand_u(double t) const {
  return lerp_at(wisp_.centre.strand_u, control_index(t));
}

double WispChart::depth(double t) const {
  return lerp_at(wisp_.centre.depth, control_index(t));
}

Vector3d WispChart::world(double t) const {
  const int n = int(strand_.world.size());
  if (n == 1) return strand_.world[0];
  return lerp_at(strand_.world, strand_u(t) * (n - 1));
}

TubeFrame WispChart::frame(double t) const {
  const Vector3d to_eye = eye_ - world(t);
  return tube_frame(tangent(t),
                    to_eye.norm() > 0 ? Vector3d(to_eye.normalized()) : Vector3d::UnitZ());
}

std::vector<double> WispChart::samples(double step_px, int per_span) const {
  const auto& s = wisp_.sections;
  const int spans = std::max(1, wisp_.centre.piece_count());
  const double max_dt = 1.0 / (spans * std::max(1, per_span));
  std::vector<double> out = {s.front().t};
  for (size_t i = 0; i + 1 < s.size(); ++i) {
    const double len = (s[i + 1].centre - s[i].centre).norm();
    const double dt = s[i + 1].t - s[i].t;
    const int n = std::max(
        {1, int(std::ceil(len / std::max(1e-3, step_px))), int(std::ceil(dt / max_dt - 1e-9))});
    for (int k = 1; k <= n; ++k) out.push_back(s[i].t + dt * k / n);
  }
  return out;
}

}  // namespace wisp::vector
