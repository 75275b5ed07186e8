// Width profile evaluation and validation.
#include "vector/width_profile.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace wisp::vector {

std::vector<std::pair<double, double>> WidthProfile::taper_controls() {
  return {{0.0, 1.0}, {1.0, 0.0}};
}

WidthProfile WidthProfile::faraj_taper() {
  return WidthProfile{};
}

WidthProfile WidthProfile::shin() {
  WidthProfile p;
  p.shape = Shape::Shin;
  p.controls.clear();
  return p;
}

WidthProfile WidthProfile::constant() {
  WidthProfile p;
  p.controls = {{0.0, 1.0}, {1.0, 1.0}};
  return p;
}

double WidthProfile::at(double u) const {
  u = std::clamp(u, 0.0, 1.0);
  if (shape == Shape::Shin) return std::max(0.0, std::sin((u + 0.2) * M_PI / 1.2));
  if (controls.empty()) return 1.0;
  if (u <= controls.front().first) return controls.front().second;
  for (size_t i = 1; i < controls.size(); ++i) {
    const auto& [u1, f1] = controls[i];
    if (u <= u1) {
      const auto& [u0, f0] = controls[i - 1];
      return u1 > u0 ? f0 + (f1 - f0) * (u - u0) / (u1 - u0) : f1;
    }
  }
  return controls.back().second;
}

void validate(const WidthProfile& profile) {
  if (profile.shape == WidthProfile::Shape::Shin) return;
  if (profile.controls.empty())
    throw std::invalid_argument("width profile: a linear profile needs at least one control");
  double previous = 0;
  for (size_t i = 0; i < profile.controls.size(); ++i) {
    const auto& [u, f] = profile.controls[i];
    const std::string where = "width profile: control " + std::to_string(i) + ": ";
    if (!std::isfinite(u) || u < 0 || u > 1)
      throw std::invalid_argument(where + "u must be in [0,1], got " + std::to_string(u));
    if (u < previous) throw std::invalid_argument(where + "controls must be sorted by u");
    if (!std::isfinite(f) || f < 0)
      throw std::invalid_argument(where + "factor must be finite and >= 0, got " +
                                  std::to_string(f));
    previous = u;
  }
}

}  // namespace wisp::vector
