// The width profile of a wisp: a factor in [0,1] along the strand that scales the wisp's
// perspective width. Faraj 2009 (section 3.2.1) interpolates control widths linearly and makes a
// pointy wisp by putting a zero at the tip; Shin et al. 2006 use sin((u + 0.2) pi / 1.2), which
// starts at half width, swells past the middle and closes at the tip.
#pragma once

#include <array>
#include <utility>
#include <vector>

#include "sim/choices.hpp"

namespace wisp::vector {

struct WidthProfile {
  enum class Shape { Linear, Shin };
  Shape shape = Shape::Linear;
  // (u, factor) pairs sorted by u in [0,1], linearly interpolated, clamped outside (Linear only).
  // Default: Faraj's pointy wisp, full width at the root, linear taper to zero at the tip.
  std::vector<std::pair<double, double>> controls = taper_controls();

  // The factor at strand parameter u in [0,1] (0 = root, 1 = tip).
  double at(double u) const;

  static WidthProfile faraj_taper();
  static WidthProfile shin();
  static WidthProfile constant();
  static std::vector<std::pair<double, double>> taper_controls();
};

// Throws std::invalid_argument when the controls are empty (Linear), unsorted, outside [0,1] in
// u, negative or not finite.
void validate(const WidthProfile& profile);

// A style names its profile by shape: "taper" is Faraj's taper (the Linear shape with
// taper_controls()), "sine" is Shin's.
constexpr std::array<sim::Choice<WidthProfile::Shape>, 2> choices(WidthProfile::Shape) {
  return {{{"taper", WidthProfile::Shape::Linear}, {"sine", WidthProfile::Shape::Shin}}};
}

}  // namespace wisp::vector
