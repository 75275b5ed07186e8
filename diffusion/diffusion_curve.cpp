// Colour and blur interpolation along a diffusion curve, and its validation.
#include "diffusion/diffusion_curve.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace wisp::diffusion {
namespace {

// Linear interpolation in a sorted stop list, clamped at both ends.
template <class Stop, class Get>
auto interpolate(const std::vector<Stop>& stops, double t, Get get) -> decltype(get(stops[0])) {
  if (t <= stops.front().t) return get(stops.front());
  if (t >= stops.back().t) return get(stops.back());
  size_t hi = 1;
  while (stops[hi].t < t) ++hi;
  const Stop& a = stops[hi - 1];
  const Stop& b = stops[hi];
  const double span = b.t - a.t;
  const float s = span > 0 ? float((t - a.t) / span) : 0.0f;
  return get(a) * (1.0f - s) + get(b) * s;
}

template <class Stop>
void check_stops(const std::vector<Stop>& stops, const std::string& what, const char* set) {
  double prev = -1;
  for (size_t i = 0; i < stops.size(); ++i) {
    const double t = stops[i].t;
    if (!std::isfinite(t) || t < 0 || t > 1)
      throw std::invalid_argument(what + ": " + set + " stop " + std::to_string(i) +
                                  " has parameter " + std::to_string(t) + " outside [0,1]");
    if (t < prev)
      throw std::invalid_argument(what + ": " + set + " stops are not sorted by parameter");
    prev = t;
  }
}

}  // namespace

Color color_at(const std::vector<ColorStop>& stops, double t) {
  if (stops.empty()) return Color::Zero();
  return interpolate(stops, t, [](const ColorStop& s) -> Color { return s.color; });
}

float blur_at(const std::vector<BlurStop>& stops, double t) {
  if (stops.empty()) return 0.0f;
  return interpolate(stops, t, [](const BlurStop& s) { return s.sigma; });
}

void validate(const DiffusionCurve& curve, const std::string& what) {
  const size_t n = curve.points.size();
  if (n < 4 || (n - 1) % 3 != 0)
    throw std::invalid_argument(what + ": has " + std::to_string(n) +
                                " control points; a cubic Bezier path needs 3k+1 (4, 7, 10, ...)");
  for (size_t i = 0; i < n; ++i)
    if (!curve.points[i].allFinite())
      throw std::invalid_argument(what + ": control point " + std::to_string(i) +
                                  " is not a finite number");
  check_stops(curve.left, what, "left colour");
  check_stops(curve.right, what, "right colour");
  check_stops(curve.blur, what, "blur");
  for (const auto* side : {&curve.left, &curve.right})
    for (size_t i = 0; i < side->size(); ++i)
      if (!(*side)[i].color.allFinite())
        throw std::invalid_argument(what + ": colour stop " + std::to_string(i) +
                                    " is not a finite number");
  for (size_t i = 0; i < curve.blur.size(); ++i)
    if (!std::isfinite(curve.blur[i].sigma) || curve.blur[i].sigma < 0)
      throw std::invalid_argument(what + ": blur stop " + std::to_string(i) +
                                  " must be a finite value >= 0");
  for (const auto& [t0, t1] : curve.active)
    if (!(t0 >= 0 && t1 <= 1 && t0 <= t1))
      throw std::invalid_argument(what + ": active interval must satisfy 0 <= t0 <= t1 <= 1");
}

void validate(const PoissonCurve& curve, const std::string& what) {
  DiffusionCurve path;
  path.points = curve.points;
  path.right = curve.weights;
  validate(path, what);
  if (curve.weights.empty()) throw std::invalid_argument(what + ": has no weights");
}

void validate(const GradientMesh& mesh, const std::string& what) {
  if (mesh.rows < 1 || mesh.cols < 1)
    throw std::invalid_argument(what + ": needs at least one row and one column of tiles");
  const size_t n = size_t(mesh.rows + 1) * size_t(mesh.cols + 1);
  const auto count = [&](size_t got, const char* name) {
    if (got != n)
      throw std::invalid_argument(what + ": " + std::to_string(got) + " " + name + " for " +
                                  std::to_string(mesh.rows) + "x" + std::to_string(mesh.cols) +
                                  " tiles; expected " + std::to_string(n));
  };
  count(mesh.positions.size(), "positions");
  count(mesh.colors.size(), "colours");
  if (!mesh.tangents_u.empty() || !mesh.tangents_v.empty()) {
    count(mesh.tangents_u.size(), "u tangents");
    count(mesh.tangents_v.size(), "v tangents");
  }
  for (const auto* set : {&mesh.positions, &mesh.tangents_u, &mesh.tangents_v})
    for (const Eigen::Vector2d& p : *set)
      if (!p.allFinite()) throw std::invalid_argument(what + ": a position is not finite");
  for (const Color& c : mesh.colors)
    if (!c.allFinite()) throw std::invalid_argument(what + ": a colour is not finite");
}

}  // namespace wisp::diffusion
