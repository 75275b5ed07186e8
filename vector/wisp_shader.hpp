// The colour field of one lit wisp over its chart (t, u): the tube lighting of
// vector/hair_shading.hpp at the strand's 3D frame, through the style's toon ramp (or the
// shadow -> hair colour blend), plus the smooth Kajiya-Kay specular. Hard band edges of the ramp
// are the level sets x(t, u) = edge of the ramp's x, which is monotone in N(u).L at each t.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "diffusion/diffusion_curve.hpp"
#include "vector/hair_style.hpp"
#include "vector/toon_ramp.hpp"
#include "vector/wisp_chart.hpp"

namespace wisp::vector {

// What every wisp of a frame shares.
struct FrameLight {
  Eigen::Vector3d light{0, 0, 1};        // unit, towards the light
  double z_near = 1, z_far = 1;          // Costigan's depth range
  Eigen::Vector3d head_centre{0, 0, 0};  // for the head's outward normal (head shadow, anime)
  double head_radius = 0;                // the roots' mean distance from head_centre
};

// The head's centre estimated from the strands' roots: the least-squares sphere through them
// (roots lie on the scalp), or their centroid when they do not pin a sphere down.
Eigen::Vector3d head_centre_from_roots(const std::vector<Eigen::Vector3d>& roots);

// What the wisps of a frame share: its light, the depth range (the style's, or the nearest and
// farthest of the wisps), the head's centre and radius from the strands' roots.
FrameLight frame_light(const sim::ProjectedFrame& frame, const std::vector<Wisp>& wisps,
                       const HairStyle& style);

class WispShader {
 public:
  // `bands`: the ramp's bands, or null for the shadow -> hair blend.
  WispShader(const WispChart& chart, const HairStyle& style, const FrameLight& light,
             const RampBands* bands);

  double x(double t, double u) const;  // the ramp's x: intensity / max intensity, in [0, 1]
  double y(double t, double u) const;  // the ramp's y: the style's metric, in [0, 1]
  int band(double t, double u) const;  // 0 without a ramp
  Eigen::Vector3f color(double t, double u) const;
  Eigen::Vector3f color_in_band(double t, double u, int band) const;
  const RampBands* bands() const { return bands_; }

 private:
  const WispChart& chart_;
  const HairStyle& style_;
  FrameLight light_;
  const RampBands* bands_;
};

// Colour stops along a curve through chart points `tu` at curve parameters `s`: the shader's
// colour at each point, and where the ramp's band changes between two points, a pair of stops at
// the band edge with the colours of both bands (a sharp step). Parameters never decrease.
std::vector<diffusion::ColorStop> stops_along(const WispShader& shader,
                                              const std::vector<Eigen::Vector2d>& tu,
                                              const std::vector<double>& s);

}  // namespace wisp::vector
