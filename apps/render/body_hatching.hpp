// Hatching on the body's surfaces (the skin's counterpart of vector/hatching.hpp): cross-contour
// lines laid on each surface in its solid's own frame (sim::ProjectedSurface::local), so they
// stick to the skin as the figure moves. Lines are the level sets local.y = i * spacing (rings
// around the neck, torso and arms, whose sweeps run along local y; latitude lines on the head)
// and, for cross-hatching in the darkest band, the same tilted by cross_angle_deg about local z.
//
// Tone nesting as in a tonal art map: the lines of one family are parallel, so the candidate that
// darkens a tone most is always the one midway in the widest gap, and the greedy order is the
// bit-reversed one. Band k of the along family holds the lines i that are multiples of
// 2^(bands - 2 - k) (every line in the last one); the darkest band adds the cross family. A line
// of band k shows where the half-Lambert shade is below body_tones[k]: lighter tones a subset
// of darker tones' lines.
//
// Each line is extracted per front triangle (linear in the vertex values, so neighbouring
// triangles meet exactly on their shared edge) and chained; it shows where its surface shows:
// outside every solid drawn before it (clearance >= 0), not under a surface drawn after it, not
// under the hair mask, inside the frame. Cuts are found by bisection on the polyline (1e-4 px),
// and the line tapers to 0 over end_taper px at them, as hair strokes do.
#pragma once

#include <vector>

#include "apps/render/picture.hpp"
#include "sim/body.hpp"
#include "vector/arrangement.hpp"
#include "vector/hair_style.hpp"

namespace wisp::render {

// One drawn piece of a hatch line on the body.
struct BodyHatch {
  InkStroke stroke;
  int surface = -1;  // index into ProjectedBody::surfaces
  int band = 0;
  bool cross = false;
  double level = 0;  // the line's value of its family's field, in scene units
};

// Nothing unless style.hatching.enabled and style.hatching.body. `hair`: the hair mask over the
// body. Widths are hatching.width scaled like ink (vector::ink_scale).
std::vector<BodyHatch> hatch_body(const sim::ProjectedBody& body, const vector::HairMask& hair,
                                  const vector::HairStyle& style, int width, int height);

// Per point: whether it shows surface s of the body: on one of its front triangles outside the
// solids drawn before it, and on none of a later surface's.
std::vector<bool> body_surface_shows(const sim::ProjectedBody& body, int s,
                                     const std::vector<Eigen::Vector2d>& points);

}  // namespace wisp::render
