// Stylised highlights as closed shapes in a wisp's chart (t, u), turned into closed diffusion
// curves by vector/inner_curves.cpp.
//  - Band (Costigan 2013, section 4.3.6): the region of the tube where the Blinn term
//    (N(u).H)^c exceeds a threshold. Along the strand it peaks where the tangent is perpendicular
//    to H (the Kajiya-Kay peak), so neighbouring wisps light up at consistent places and the
//    highlights line up into a band across the hair.
//  - Anime (Shin 2006, section 5.4.2, after Anjyo and Hiramitsu; the "angel ring" of anime hair):
//    one band on the head, cut out of every wisp that crosses it. Hair combed from the crown runs
//    along the head's meridians, and a strand's Kajiya-Kay highlight sits where its tangent is
//    perpendicular to the half-vector H = normalize(L + V): on a meridian, where the head's
//    normal has H's elevation. So the band is the ring of head directions whose latitude (about
//    the head's crown axis) is within `band_width_deg` / 2 of H's elevation, over the longitudes
//    within `band_extent_deg` of H's (where the head faces the light and the eye), narrowing to a
//    point at both ends. Its lower (tip-side) edge is a zigzag of teeth `tooth_depth` times the
//    band's width long, `teeth` of them across a wisp's width; being laid on the head, the teeth
//    and edges continue from one wisp to its neighbours. Shin found candidate points per strand
//    and linked them across strands into triangle strips; laying the band on the head does that
//    linking by construction, and smoothly: the pieces never come out as scattered shards.
// All shapes are polygons in (t, u), counter-clockwise (inside on the left), within
// |u| <= max_width, so they stay inside their wisp.
//
// Where a wisp in front crosses another's highlight, its outline's outside would carry the shadow
// colour into the highlight (Faraj's overlap shading) and smear it towards its edge; so outlines
// take the highlight colour outside wherever a visible highlight lies just beyond them
// (HighlightCover), and a band runs crisply from one wisp to the next.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "diffusion/diffusion_curve.hpp"
#include "sim/projected.hpp"
#include "vector/hair_style.hpp"
#include "vector/visible_region.hpp"
#include "vector/wisp_chart.hpp"

namespace wisp::vector {

using ChartPolygon = std::vector<Eigen::Vector2d>;

// Band highlights of one wisp: closed level sets of the Blinn term at `style.threshold`, sampled
// at the chart parameters `ts` and 17 lateral positions.
std::vector<ChartPolygon> band_highlights(const WispChart& chart, const std::vector<double>& ts,
                                          const HighlightStyle& style,
                                          const Eigen::Vector3d& light);

// The anime band of a frame, on the head (see above); angles in radians.
struct AnimeBand {
  Eigen::Vector3d centre{0, 0, 0};  // the head's centre
  Eigen::Vector3d up{0, 1, 0};      // its crown axis
  Eigen::Vector3d front{0, 0, 1};   // horizontal (perpendicular to up), towards H
  Eigen::Vector3d side{1, 0, 0};    // up x front
  double latitude = 0;              // of the band's middle line: H's elevation
  double half_width = 0;            // where the band is widest (at H's longitude)
  double extent = 0;                // longitudes within +-extent of H's
  double period = 1;                // of the teeth, in longitude
  double tooth = 1;                 // tooth length, in band widths
  double focal_px = 1;              // for the wisps' widths in scene units

  // Inside the band: the angular distance from the direction of p (from the centre) to the
  // band's nearest edge, > 0 inside and < 0 outside; continuous.
  double field(const Eigen::Vector3d& p) const;
};

// The frame's band: the head's centre (the roots' sphere), its radius (the roots' mean distance
// from it, for the teeth's spacing in longitude: `teeth` per wisp width `wisp_width`), the
// frame's light, eye, head axis and focal length.
AnimeBand anime_band(const HighlightStyle& style, const sim::ProjectedFrame& frame,
                     const Eigen::Vector3d& head_centre, double head_radius, double wisp_width);

// The band cut out of one wisp: the closed level sets of AnimeBand::field at 0 over the wisp's
// surface (its centre line offset across by its half-width along the tube's lateral axis B),
// sampled at the chart parameters `ts` and 17 lateral positions within |u| <= max_width.
std::vector<ChartPolygon> anime_highlights(const WispChart& chart, const std::vector<double>& ts,
                                           const HighlightStyle& style, const AnimeBand& band);

// Chart points along a polygon's edges, at most `step_t` in t and `step_u` in u apart, so the
// polygon mapped to pixels follows the chart's bending.
std::vector<Eigen::Vector2d> densify(const ChartPolygon& poly, double step_t, double step_u);

// A highlight's outline densified for its wisp: steps no longer than the spacing of the wisp's
// `sample_count` shading samples along it (at least 8 over the chart) and 0.1 across.
std::vector<Eigen::Vector2d> highlight_outline(const WispChart& chart, size_t sample_count,
                                               const ChartPolygon& poly);

// The highlights of a frame in pixels, each visible where its wisp is (VisibleRegions).
class HighlightCover {
 public:
  explicit HighlightCover(const VisibleRegions& regions) : regions_(regions) {}

  void add(int wisp, std::vector<Eigen::Vector2d> ring);
  bool empty() const { return rings_.empty(); }
  // Whether p lies in a visible highlight of a wisp other than `except`.
  bool contains(const Eigen::Vector2d& p, int except) const;
  // The outside colours of wisp w's outline (diffusion's right): `shadow`, and `highlight` where
  // a visible highlight of another wisp lies 0.75 px beyond the outline, with a sharp step at
  // each change (sampled every pixel, located by bisection to 1e-4 of the outline).
  std::vector<diffusion::ColorStop> outside_stops(const Wisp& wisp, int w,
                                                  const Eigen::Vector3f& shadow,
                                                  const Eigen::Vector3f& highlight) const;

 private:
  struct Ring {
    int wisp;
    std::vector<Eigen::Vector2d> points;
    Eigen::AlignedBox2d box;
  };
  const VisibleRegions& regions_;
  std::vector<Ring> rings_;
};

}  // namespace wisp::vector
