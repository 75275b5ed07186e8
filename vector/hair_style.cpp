// The ranges of a hair style's fields: see hair_style.hpp. These are the only checks of them; the
// scene reader reports their messages with the file and "style." in front.
#include "vector/hair_style.hpp"

#include <string>
#include <tuple>
#include <utility>

#include "sim/params.hpp"

namespace wisp::vector {

using sim::require;

void validate(const ShadingStyle& s) {
  require(s.band_threshold > 0 && s.band_threshold <= 1, "band_threshold",
          "must be in (0, 1] (a colour difference)");
  const Lighting& l = s.lighting;
  for (const auto& [weight, field] : {std::pair{l.ambient, "ambient"},
                                      {l.kajiya_diffuse, "kajiya_diffuse"},
                                      {l.lambert, "lambert"},
                                      {l.specular, "specular"}})
    require(weight >= 0 && weight <= 10, field, "must be a weight in [0, 10]");
  require(l.shininess > 0 && l.shininess <= 10000, "shininess", "must be in (0, 10000]");
  require(l.head_shadow >= 0 && l.head_shadow <= 1, "head_shadow", "must be in [0, 1]");
  require(l.head_offset >= -1 && l.head_offset <= 1, "head_offset", "must be in [-1, 1]");
  require(l.back_exponent >= 0 && l.back_exponent <= 100, "back_exponent", "must be in [0, 100]");
  require(s.depth_near >= 0, "depth_near", "must be >= 0 metres (0: the frame's nearest hair)");
  require(s.depth_far >= 0, "depth_far", "must be >= 0 metres (0: the frame's farthest hair)");
  require(s.depth_near == 0 || s.depth_far == 0 || s.depth_far > s.depth_near, "depth_far",
          "must be greater than depth_near");
  require(s.metric_shininess > 0 && s.metric_shininess <= 10000, "metric_shininess",
          "must be in (0, 10000]");
  require(s.sample_px >= 0.25 && s.sample_px <= 100, "sample_px", "must be in [0.25, 100] pixels");
}

void validate(const HighlightStyle& h) {
  require(h.threshold > 0 && h.threshold < 1, "threshold", "must be in (0, 1)");
  require(h.shininess > 0 && h.shininess <= 10000, "shininess", "must be in (0, 10000]");
  require(h.max_width > 0 && h.max_width <= 1, "max_width",
          "must be in (0, 1] (a fraction of the wisp's half-width)");
  require(h.teeth >= 1 && h.teeth <= 16, "teeth", "must be in [1, 16]");
  require(h.band_width_deg > 0 && h.band_width_deg <= 90, "band_width_deg",
          "must be in (0, 90] degrees");
  require(h.band_extent_deg >= 1 && h.band_extent_deg <= 180, "band_extent_deg",
          "must be in [1, 180] degrees");
  require(h.band_shift_deg >= -90 && h.band_shift_deg <= 90, "band_shift_deg",
          "must be in [-90, 90] degrees");
  require(h.tooth_depth >= 0 && h.tooth_depth <= 10, "tooth_depth",
          "must be in [0, 10] band widths");
}

void validate(const InkStyle& k) {
  for (const auto& [width, lines] :
       {std::pair{k.silhouette_width, "silhouette"}, {k.occlusion_width, "occlusion"}})
    require(width >= 0 && width <= 1000, std::string(lines) + "_width",
            std::string("must be a width in [0, 1000] pixels (0: no ") + lines + " ink)");
  require(k.reference_size >= 1 && k.reference_size <= 65536, "reference_size",
          "must be in [1, 65536] pixels");
  // The tapers at both ends: over a fraction of the strand, down to a width factor.
  for (const auto& [fade, width, end] :
       {std::tuple{k.root_fade, k.root_width, "root"}, {k.tip_fade, k.tip_width, "tip"}}) {
    require(fade >= 0 && fade <= 1, std::string(end) + "_fade",
            "must be in [0, 1] (a fraction of the strand; 0: no taper)");
    require(width >= 0 && width <= 1, std::string(end) + "_width",
            std::string("must be in [0, 1] (the width factor at the ") + end + ")");
  }
  require(k.end_taper >= 0, "end_taper", "must be >= 0 pixels");
  require(k.fit_tolerance > 0 && k.fit_tolerance <= 5, "fit_tolerance", "must be in (0, 5] pixels");
}

void validate(const BaseStyle& b) {
  require(b.tone >= 0 && b.tone <= 1, "tone",
          "must be in [0, 1] (0: the shadow colour, 1: the hair colour)");
  require(b.spread >= 0.25 && b.spread <= 8, "spread", "must be in [0.25, 8] root spacings");
  require(b.level > 0 && b.level < 1, "level", "must be in (0, 1) (a coverage level)");
}

void validate(const BlurStyle& b) {
  require(b.tip >= 0 && b.tip <= 256, "tip", "must be in [0, 256] pixels (0: sharp tips)");
  require(b.tip_fade > 0 && b.tip_fade <= 1, "tip_fade",
          "must be in (0, 1] (a fraction of the strand)");
  require(b.shutter >= 0 && b.shutter <= 1, "shutter",
          "must be in [0, 1] (a fraction of a frame; 0: no motion blur)");
  require(b.max > 0 && b.max <= 256, "max", "must be in (0, 256] pixels");
  require(b.reference_size >= 1 && b.reference_size <= 65536, "reference_size",
          "must be in [1, 65536] pixels");
}

void validate(const HatchStyle& h) {
  require(!h.tones.empty() && h.tones.size() <= 8, "tones", "must list 1 to 8 tone levels");
  require(h.coverage.size() == h.tones.size(), "coverage", "must have one entry per tone level");
  for (size_t k = 0; k < h.tones.size(); ++k) {
    require(h.tones[k] > 0 && h.tones[k] <= 1 && (k == 0 || h.tones[k] < h.tones[k - 1]), "tones",
            "must be descending, in (0, 1]");
    require(
        h.coverage[k] > 0 && h.coverage[k] <= 0.9 && (k == 0 || h.coverage[k] > h.coverage[k - 1]),
        "coverage", "must be ascending, in (0, 0.9]");
  }
  require(h.cross_angle_deg >= 10 && h.cross_angle_deg <= 90, "cross_angle_deg",
          "must be in [10, 90] degrees");
  require(h.width > 0 && h.width <= 100, "width", "must be in (0, 100] pixels");
  require(h.length >= 1e-3 && h.length <= 1, "length", "must be in [0.001, 1] scene units");
  require(h.length_jitter >= 0 && h.length_jitter < 1, "length_jitter", "must be in [0, 1)");
  require(h.lanes >= 2 && h.lanes <= 64, "lanes", "must be in [2, 64]");
  require(h.reach > 0 && h.reach <= 1, "reach", "must be in (0, 1] (a fraction of the half-width)");
  require(h.candidates >= 1 && h.candidates <= 100, "candidates", "must be in [1, 100]");
  require(h.soft >= 0 && h.soft <= 0.5, "soft", "must be in [0, 0.5]");
  require(h.end_taper >= 0 && h.end_taper <= 100, "end_taper", "must be in [0, 100] pixels");
  require(!h.body_tones.empty() && h.body_tones.size() <= 6, "body_tones",
          "must list 1 to 6 tone levels");
  for (size_t k = 0; k < h.body_tones.size(); ++k)
    require(h.body_tones[k] > 0 && h.body_tones[k] <= 1 &&
                (k == 0 || h.body_tones[k] < h.body_tones[k - 1]),
            "body_tones", "must be descending, in (0, 1]");
  require(h.body_spacing >= 1e-4 && h.body_spacing <= 1, "body_spacing",
          "must be in [0.0001, 1] scene units");
}

void validate(const HairStyle& s) {
  require(s.geometry.width > 0 && s.geometry.width <= 1, "width",
          "must be a width in (0, 1] metres");
  require(s.geometry.root_taper >= 0 && s.geometry.root_taper <= 1, "root_taper",
          "must be in [0, 1] (a fraction of the strand; 0: no taper)");
  require(s.geometry.curvature_clamp > 0, "curvature_clamp",
          "must be > 0 (null disables the clamp)");
  require(s.geometry.flatten_tolerance_px >= 0.005 && s.geometry.flatten_tolerance_px <= 2,
          "flatten_tolerance", "must be in [0.005, 2] pixels");
  require(s.highlight_along >= 0 && s.highlight_along <= 1, "highlight_along", "must be in [0, 1]");
  require(s.highlight_spread > 0 && s.highlight_spread <= 1, "highlight_spread",
          "must be in (0, 1]");
  sim::validate_part(s.shading, "shading");
  sim::validate_part(s.specular, "highlights");
  sim::validate_part(s.ink, "ink");
  sim::validate_part(s.base, "base");
  sim::validate_part(s.blur, "blur");
  sim::validate_part(s.hatching, "hatching");
  sim::validate_part(s.fur, "fur");
  const Lighting& l = s.shading.lighting;
  require(s.shading.model != ShadingModel::Lit || l.ambient + l.kajiya_diffuse + l.lambert > 0,
          "shading", "lit shading needs a positive ambient, kajiya_diffuse or lambert weight");
}

}  // namespace wisp::vector
