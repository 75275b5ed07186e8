// Blur along the hair (Orzan et al. 2008, section 3.3; Faraj 2009 names it for wisps without
// giving values): every visible wisp's outline carries blur values, which diffuse over the frame
// into a blur map (diffusion/blur.hpp) that reblurs the hair, its mask and its ink
// (apps/render/picture.hpp). The blur at a point of an outline is a Gaussian sigma in pixels; its
// three sources (BlurStyle) add as variances, and the sum is capped at BlurStyle::max:
//  - soft tips: BlurStyle::tip, rising as a smoothstep over the last tip_fade of the strand;
//  - depth of field: a thin lens of aperture diameter A focused on the plane at distance z_f
//    images a point at planar depth z (along the view axis) as a disc of diameter
//    c = focal_px A |1/z_f - 1/z| pixels (the circle of confusion); its sigma is c / 4, the
//    standard deviation of a uniform disc of diameter c along any axis;
//  - motion: a sample that moves v px between this frame and its neighbour is smeared over
//    shutter * v px by a shutter open that fraction of the frame, a box of sigma
//    shutter * v / sqrt(12); applied isotropically (softness, not a directional streak).
#pragma once

#include <utility>
#include <vector>

#include "diffusion/diffusion_curve.hpp"
#include "sim/projected.hpp"
#include "vector/arrangement.hpp"
#include "vector/hair_style.hpp"
#include "vector/wisp.hpp"

namespace wisp::vector {

// The camera's lens (the scene's camera.focus_distance and camera.aperture), scene units.
struct Lens {
  double focus_distance = 1;  // from the eye to the plane in focus, along the view axis
  double aperture = 0;        // the aperture's diameter; 0: a pinhole, all in focus
};

// The diameter in pixels of the circle of confusion of a point at planar depth z (> 0).
double circle_of_confusion_px(const Lens& lens, double focal_px, double z);

// Whether the style and lens blur anything at all; false: frames are exactly the sharp ones.
bool blurs(const BlurStyle& style, const Lens& lens);

struct BlurSources {
  Lens lens;
  // The frame just before this one (or after it, for the first frame), whose strands with the
  // same id and sample count give each sample's motion; null: no motion.
  const sim::ProjectedFrame* neighbour = nullptr;
};

// The curves of the blur map (diffusion::solve_blur_map), without colours: one per wisp with a
// visible interval, its outline active where it shows with a blur stop at every on-curve point,
// then the occluder cuts of the silhouette (WispArrangement::occluder_cuts) as sharp curves
// (sigma 0): the body in front is drawn sharp, so the hair's blur must not spill over its edge.
// Empty when no stop exceeds 0.
std::vector<diffusion::DiffusionCurve> blur_curves(const sim::ProjectedFrame& frame,
                                                   const std::vector<Wisp>& wisps,
                                                   const WispArrangement& arrangement,
                                                   const BlurStyle& style,
                                                   const BlurSources& sources);

}  // namespace wisp::vector
