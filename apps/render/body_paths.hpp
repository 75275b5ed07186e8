// The body's surfaces as a few filled paths of flat skin tones, without seams. Filling a surface
// one anti-aliased triangle at a time lets the background bleed through every shared edge (the
// conflation artefact: two half-covered pixels do not make a covered one), in Cairo as in every
// SVG viewer. Here each tone region of a surface is the union of its triangle pieces, filled as
// ONE path: only the region's outline is drawn, never an interior edge.
//
// The union costs no polygon clipping: the pieces are front faces, all turning the same way in
// the image, so the winding number of their outlines summed is the number of pieces over a
// point; each edge shared by two pieces is traversed once each way and cancels. What is left is
// the outline (holes turning the other way), and the nonzero fill rule fills exactly the union.
// Shared edges are found exactly, by the identity of their end points: a mesh vertex, the
// crossing of a level on a mesh edge (computed once from that edge, so both triangles agree), or
// the crossing of the two levels inside one triangle.
//
// Per surface (ProjectedSurface, drawn back to front): the pieces are the front faces cut where
// the surface runs inside a solid drawn before it (clearance 0), split by the light's
// half-Lambert shade at `threshold` (the terminator). The two tones never meet edge to edge: the
// lit tone is filled first and reaches `overlap` px under the shadow (to an offset of the
// terminator, the shade's level divided by its image gradient), then the shadow region on top,
// so no seam can open between them. Filling the whole silhouette in the lit tone would do that
// too, but where the shadow reaches the silhouette, both fills' anti-aliased edges would fall on
// the same pixels and leave a lit fringe along it (the same conflation); with the offset, that
// happens only within `overlap` px of where the terminator meets the silhouette.
//
// Outlines are smoothed into cubic Beziers (vector::fit_cubics, within `tolerance` px of the
// exact polylines): the silhouette, the cut and the terminator, the last being the shade's level
// interpolated across the triangles, not their edges. Both fills break their outlines wherever
// either changes course, so the silhouette they share is the very same cubics in both.
#pragma once

#include <vector>

#include "apps/render/picture.hpp"
#include "sim/body.hpp"

namespace wisp::render {

struct BodyTones {
  Rgb lit{0.96f, 0.80f, 0.69f}, shadow{0.69f, 0.58f, 0.50f};
  float threshold = 0.45f;  // half-Lambert shade below which the shadow tone shows
  double tolerance = 0.05;  // px: largest distance of the fitted outlines from the exact ones
  double overlap = 2;       // px: how far the lit fill reaches under the shadow
};

// Per surface in drawing order: its lit fill, then its shadow region (each when not empty).
std::vector<BodyPath> body_paths(const sim::ProjectedBody& body, const BodyTones& tones);

// The facial features' visible runs (sim::BodyModel::face) as ink strokes in `color`: smooth
// cubic paths through the samples (centripetal Catmull-Rom, vector/bezier.hpp) with their widths.
std::vector<InkStroke> face_strokes(const std::vector<sim::FaceStroke>& runs, const Rgb& color);

// A frame's body layer: the skin's tone regions, then the face's lines; the projected surfaces
// they were drawn from (for hatching on them, apps/render/body_hatching.hpp); and the fur growing
// on it, which the picture draws over the hair (FramePicture::fur).
struct BodyLayer {
  std::vector<BodyPath> paths;
  std::vector<InkStroke> face;
  sim::ProjectedBody projected;
  std::vector<vector::FurTuft> fur;
};

}  // namespace wisp::render
