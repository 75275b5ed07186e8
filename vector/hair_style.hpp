// How hair looks: wisp geometry, the colours that become each wisp's diffusion curves, stylised
// highlights and ink. The scene's `style` part fills it (io/scene_json.cpp), usually from a
// preset in data/styles/ (docs/style.md).
//
// Two shading models:
//  - Faraj (2009, section 3.2.2): the hair colour inside every wisp, a shadow colour outside (so
//    overlapping wisps shade each other), and one colour point, always on the same side of every
//    wisp, which makes the hair look lit by a fixed light. The `faraj` preset and the default.
//  - Lit: the light of the frame on each wisp as a tube (vector/hair_shading.hpp), through a 2D
//    toon ramp (X-Toon, vector/toon_ramp.hpp) or a blend from the shadow to the hair colour,
//    written as colour stops along the outline, a centre line, and extra curves at the ramp's hard
//    band edges; the shading follows the light as the head turns.
// Highlights (Costigan's Blinn band or Shin's anime zigzags) are closed diffusion curves inside
// their wisps, and ink strokes follow the arrangement's silhouette and occlusion lines.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "vector/fur.hpp"
#include "vector/hair_shading.hpp"
#include "vector/toon_ramp.hpp"
#include "vector/wisp.hpp"

namespace wisp::vector {

enum class ShadingModel { Faraj, Lit };
constexpr std::array<sim::Choice<ShadingModel>, 2> choices(ShadingModel) {
  return {{{"faraj", ShadingModel::Faraj}, {"lit", ShadingModel::Lit}}};
}

struct ShadingStyle {
  ShadingModel model = ShadingModel::Faraj;
  // Lit: the ramp giving the colour at (intensity, metric); null blends from the shadow colour at
  // intensity 0 to the hair colour at 1.
  std::shared_ptr<const ToonRamp> ramp;
  RampMetric metric = RampMetric::None;  // the ramp's y; None reads its middle row
  Eigen::Vector3f ramp_tint{1, 1, 1};    // multiplies the ramp's colours (a grey ramp + a tint)
  bool hard_bands = true;                // extra curves at the ramp's band edges
  double band_threshold = 0.06;          // colour jump between ramp columns that makes an edge
  Lighting lighting;
  // Costigan's depth range in scene units; 0: the nearest and farthest hair of the frame.
  double depth_near = 0, depth_far = 0;
  double metric_shininess = 20;  // exponent of the Blinn term when the metric is Specular
  bool centre_line = true;       // a curve along each wisp's centre carrying its colour there
  double sample_px = 2;          // spacing of the shading samples along a wisp, pixels
};

enum class HighlightShape { None, Band, Anime };
constexpr std::array<sim::Choice<HighlightShape>, 3> choices(HighlightShape) {
  return {{{"none", HighlightShape::None},
           {"band", HighlightShape::Band},
           {"anime", HighlightShape::Anime}}};
}

// Stylised highlights as closed diffusion curves: the highlight colour inside, an insulating
// (Neumann) side outside, so the wisp's shading around them is undisturbed.
struct HighlightStyle {
  HighlightShape shape = HighlightShape::None;
  Eigen::Vector3f color{1.0f, 0.95f, 0.85f};
  // Band: the region where the tube's Blinn term (N.H)^shininess exceeds `threshold`.
  double threshold = 0.5;
  double shininess = 40;
  double max_width = 0.8;  // highlights stay within |u| <= this across the wisp
  // Anime: a ring on the head at H's elevation (vector/highlights.hpp), in degrees of latitude
  // and longitude about the head's crown axis.
  double band_width_deg = 8;    // the ring's width where it is widest
  double band_extent_deg = 75;  // longitudes within this of H's; it closes to a point there
  double band_shift_deg = 0;    // moves the ring up (towards the roots) or down
  int teeth = 2;                // zigzag teeth per wisp width along its lower edge
  double tooth_depth = 1;       // tooth length, in ring widths
};

// Ink along the silhouette and occlusion boundaries (vector/ink_strokes.hpp).
struct InkStyle {
  // Stroke widths in pixels of an image whose shorter side is `reference_size` pixels; scaled by
  // min(width, height) / reference_size, so strokes keep their size relative to the frame.
  double silhouette_width = 0;  // 0: no silhouette ink
  double occlusion_width = 0;   // 0: no occlusion ink
  double reference_size = 512;
  Eigen::Vector3f color{0.10f, 0.06f, 0.05f};
  // Strokes narrow towards the roots (Costigan and Shin fade them there, where wisps pile up and
  // their order jumps): width factor root_width at the root rising smoothly to 1 at strand
  // parameter root_fade. root_fade 0: no taper.
  double root_fade = 0.3;
  double root_width = 0.3;
  // Likewise towards the tips, over the last tip_fade of the strand, so thin tips do not end in
  // blobs of ink.
  double tip_fade = 0.15;
  double tip_width = 0.35;
  double end_taper = 6;  // px (reference): occlusion strokes taper to 0 at their open ends
  // px (final image): Bezier fit of the polylines. At 0.15 px the 1:1 error of the toon and anime
  // presets at 512^2 was 2-3/255 higher at the 99th percentile (an ink edge off by a tenth of a
  // pixel against skin is 20/255); the strokes cost a few milliseconds either way.
  double fit_tolerance = 0.05;

  bool enabled() const { return silhouette_width > 0 || occlusion_width > 0; }
};

// The hair base (vector/hair_base.hpp): the scalp region the roots grow from, painted under the
// wisps. Its region is the scalp's coverage field (sim/scalp.hpp) above `level`; its colour is
// `tone` of the way from the shadow colour to the hair colour, or with a toon ramp the ramp's
// colour at x = tone (its middle row), so it reads as the dark base coat of the hair's own
// palette. Inside, the solve blends it with the shadow colour that the wisps' outsides carry.
struct BaseStyle {
  bool enabled = true;
  double tone = 0.6;
  double spread = 1.0;  // the coverage kernel's width, in root spacings
  double level = 0.5;   // the hairline: lower reaches farther beyond the outermost roots
};

// Blur along the hair (Orzan et al. 2008, used by Faraj): blur values on every wisp's outline,
// diffused into a blur map that reblurs the hair, its mask and its ink (vector/hair_blur.hpp).
// Three sources, added as variances: soft tips, depth of field (the camera's lens:
// camera.aperture and camera.focus_distance) and motion. All zero (the default): no blur.
struct BlurStyle {
  // Sigma (px of an image whose shorter side is `reference_size`) at the tips, rising smoothly
  // from 0 over the last `tip_fade` of the strand. 0: sharp tips.
  double tip = 0;
  double tip_fade = 0.3;
  // The fraction of a frame the shutter stays open: a sample that moves v px per frame is
  // softened by the sigma of a v * shutter px long smear (isotropic: softness, not streaks).
  double shutter = 0;
  double max = 24;  // px (reference): no sigma exceeds this
  double reference_size = 512;
};

// Pen hatching in the shadows (Costigan 2013, section 4.3.8, after Praun's tonal art maps;
// vector/hatching.hpp): strokes laid in each wisp's own (along, across) coordinates, ordered once
// by their effect on tone, a prefix of that order per tone band, cross-hatching in the darkest.
struct HatchStyle {
  bool enabled = false;
  // Tone bands by the shading's x (light intensity over its maximum, vector/wisp_shader.hpp):
  // band k is where x < tones[k] (descending), filled to ink coverage coverage[k] (ascending).
  std::vector<double> tones = {0.62, 0.46, 0.32};
  std::vector<double> coverage = {0.12, 0.24, 0.42};
  bool cross = true;            // the darkest band adds strokes across the hair
  double cross_angle_deg = 40;  // their angle to the hair
  double width = 1.4;           // px of a frame whose shorter side is ink.reference_size
  double length = 0.09;         // scene units along the hair (big strokes: Costigan's users)
  double length_jitter = 0.35;  // +- this fraction of `length`
  int lanes = 8;                // the coverage grid's columns across a wisp
  double reach = 0.85;          // strokes keep within |u| <= reach across a wisp
  int candidates = 10;          // random candidates per stroke; the best for tone is kept
  double soft = 0.04;           // strokes fade in over this much x below their band's tone
  double end_taper = 3;         // px (reference): strokes taper to 0 where they are clipped
  Eigen::Vector3f color{0.10f, 0.06f, 0.05f};
  std::uint64_t seed = 1;
  // On the body (apps/render/body_hatching.hpp): cross-contour lines `body_spacing` scene units
  // apart in the darkest band, one tone per band by the skin's half-Lambert shade (descending;
  // the skin's shadow tone starts at 0.45).
  bool body = true;
  std::vector<double> body_tones = {0.52, 0.42, 0.3};
  double body_spacing = 0.006;
};

struct HairStyle {
  // A wisp stands for a clump of hair: about 2.8 cm wide at the root, so that some 150 guides
  // cover a head.
  WispStyle geometry = [] {
    WispStyle g;
    g.width = 0.028;
    return g;
  }();
  Eigen::Vector3f hair{0.42f, 0.25f, 0.13f};       // inside colour, linear RGB in [0,1]
  Eigen::Vector3f shadow{0.10f, 0.06f, 0.04f};     // outside colour
  Eigen::Vector3f highlight{0.80f, 0.58f, 0.34f};  // Faraj's colour point
  double highlight_along = 0.35;   // where the colour point sits along the wisp (0 root, 1 tip)
  double highlight_spread = 0.25;  // its extent along the wisp, as a fraction of the length
  bool highlight_on_left = true;   // which side of every wisp carries it
  ShadingStyle shading;
  HighlightStyle specular;
  InkStyle ink;
  BaseStyle base;
  BlurStyle blur;
  HatchStyle hatching;
  FurStyle fur;  // fur tufts, when the scene grows fur (vector/fur.hpp)
};

// Each throws std::invalid_argument("field: what") for the first field out of its range, the
// field named as in the scene's `style` part (docs/style.md): "ink.tip_fade: must be in [0, 1]
// ...". io/ puts the file and "style." in front. The HairStyle checks the wisp geometry a style
// sets (width, curvature_clamp) and its three parts; build_wisps checks the whole WispStyle.
void validate(const ShadingStyle& shading);  // with its Lighting, whose fields sit beside its own
void validate(const HighlightStyle& highlights);
void validate(const InkStyle& ink);
void validate(const BaseStyle& base);
void validate(const BlurStyle& blur);
void validate(const HatchStyle& hatching);
void validate(const HairStyle& style);

}  // namespace wisp::vector
