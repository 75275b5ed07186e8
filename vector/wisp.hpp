// Wisps: the 2D shapes of projected guide strands (Faraj 2009, section 3.2.1). A strand's projected
// samples become a centre spline B(t); the wisp is the band p = B(t) +- N(t) d(t) around it,
// closed root -> tip along the left side and tip -> root along the right side. The half-width
// d(t) is the style's world width scaled by perspective and the width profile (or, for a guide
// that stands for a clump of a dense groom, the clump's width it carries); each side is then
// limited by the nearby centres of curvature on that side so the offset never folds over itself
// (Faraj could not render curly hair because his offsets looped). The outline is a cubic Bezier
// path with depth per control point; its flattening (the sections of the band) feeds the
// arrangement.
//
// Coordinates are pixels (x right, y down). Side::Left and Side::Right name the sides as seen on
// screen: for a direction of travel d, Left lies towards (d.y, -d.x). diffusion/ names sides the
// mathematical way (its left is (-d.y, d.x)), so a wisp's Left side is diffusion's right, and the
// wisp interior lies on diffusion's *left* of the outline; in (x, y) the outline turns
// counter-clockwise: winding +1.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "diffusion/bezier.hpp"
#include "sim/projected.hpp"
#include "vector/width_profile.hpp"

namespace wisp::vector {

struct WispStyle {
  double width = 0.01;  // full wisp width in scene units where the profile is 1
  WidthProfile profile = WidthProfile::faraj_taper();
  // Over the first `root_taper` of the strand (its parameter, 0 root to 1 tip) the width grows
  // from 0 to the profile's, as sin(pi/2 u / root_taper): the wisp starts at a point on the
  // scalp instead of a cut end. 0: the profile alone.
  double root_taper = 0.1;
  double max_width_px = 200;  // cap on the half-width, for strands very close to the eye
  // Each side's half-width <= curvature_clamp * the distance to any nearby centre of curvature
  // on that side (at the point itself: the radius of curvature); < 1 leaves margin for the
  // fitting and flattening tolerances. Infinity disables the clamp (Faraj's behaviour).
  double curvature_clamp = 0.8;
  double fit_tolerance_px = 0.05;      // outline cubic versus the exact offset curve
  double flatten_tolerance_px = 0.05;  // band polygon versus the outline cubics
  int max_pieces_per_cubic = 256;      // guard against absurd geometry
  // Build each wisp from the longest run of samples marked visible (head occlusion); a strand
  // with no visible pair of samples gives no wisp. When false every sample is used.
  bool trim_hidden = true;
  double merge_distance_px = 1e-3;  // consecutive samples closer than this are merged
  // Samples farther than this from the image origin are treated as hidden (strands crossing
  // the eye plane project to absurd coordinates).
  double max_coordinate_px = 1e6;
};

// Throws std::invalid_argument naming the field that is out of range.
void validate(const WispStyle& style);

enum class Side : std::uint8_t { Left, Tip, Right, Root };
const char* to_string(Side side);

// The centre curve: a centripetal Catmull-Rom spline through the kept samples (vector/
// catmull_rom.hpp), one piece (span) per pair of kept samples. Its parameter t in [0,1] runs
// uniformly over the spans (span i covers [i/k, (i+1)/k]).
struct CentreSpline : diffusion::BezierPath {
  std::vector<double> depth;             // per control point; linear in t within a span
  std::vector<Eigen::Vector3d> tangent;  // unit 3D tangent per control point (zero if not given)
  std::vector<double> strand_u;          // strand parameter (sample / (samples-1)) per point
};

// The outline: a closed path (last point == first), as the outline diffusion curves take it;
// its parameter s in [0,1] runs uniformly over its K cubics.
struct Outline : diffusion::BezierPath {
  std::vector<double> depth;  // per control point: the depth of B(t) at the point's t
  std::vector<double> t;      // centre parameter per control point
  std::vector<Side> side;     // per cubic
};

// One cross-section of the flattened band at centre parameter t. Consecutive sections bound the
// band's cells; the outline polygon is left[0..n] then right[n..0].
struct Section {
  double t = 0;
  double depth = 0;
  Eigen::Vector2d centre, left, right;
  double s_left = 0, s_right = 0;  // outline parameters of `left` and `right`
};

struct Wisp {
  int strand = -1;       // sim::ProjectedStrand::id
  int first_sample = 0;  // samples [first_sample, last_sample] were used
  int last_sample = 0;
  CentreSpline centre;
  // Half-widths (px) of the left and right side at each on-curve centre point (after limits).
  std::vector<double> half_width_left, half_width_right;
  Outline outline;
  std::vector<Section> sections;  // root to tip, at least 2
  Eigen::AlignedBox2d bounds;     // of the band polygon
};

// A vertex of the flattened outline polygon with the outline parameter and depth there; `side` is
// that of the polygon edge starting at this vertex. Consecutive duplicates are removed, the
// polygon is implicitly closed.
struct OutlineVertex {
  Eigen::Vector2d p;
  double s = 0;
  double t = 0;  // centre parameter of the vertex's section
  double depth = 0;
  Side side = Side::Left;
};
std::vector<OutlineVertex> outline_polygon(const Wisp& wisp);
// The polygon of the band between sections first < last alone: left[first..last], then
// right[last..first]; its caps are the two sections' lines across the band (Side::Tip at `last`,
// Side::Root at `first`), with the sections' outline parameters.
std::vector<OutlineVertex> outline_polygon(const Wisp& wisp, int first, int last);

// Builds one wisp per strand that has at least two distinct (visible) samples, in strand order.
// Zero-length strands are skipped. Throws std::invalid_argument naming the strand and sample for
// non-finite coordinates, non-positive depth, mismatched array sizes, a non-positive focal length.
std::vector<Wisp> build_wisps(const sim::ProjectedFrame& frame, const WispStyle& style);

// One strand; nothing when it has fewer than two distinct usable samples.
std::optional<Wisp> build_wisp(const sim::ProjectedStrand& strand, double focal_px,
                               const WispStyle& style);

}  // namespace wisp::vector
