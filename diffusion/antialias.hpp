// Anti-aliasing of a solved diffusion-curve image, without solving at a higher resolution.
//
// The solve places every colour discontinuity (an active curve) between pixel centres, so a pixel
// that a sharp curve crosses shows the colour of one side only: a one-pixel staircase along every
// curve. Each such pixel is re-sampled instead: n x n sub-samples, each coloured from the nearest
// pixel centre (among the pixel's own and its eight neighbours) that it reaches in a straight line
// without crossing an active curve, and averaged. So each side of a curve contributes in
// proportion to the area it covers in the pixel, with its own solved colour, and colours never
// bleed across a curve. A sub-sample that reaches no centre (inside a feature thinner than the
// pixel spacing, which holds no pixel centre) takes the colour of the nearest curve's side that
// faces it. Curves are flattened exactly as the rasterizer flattens them, so the geometry is the
// one the solve saw.
#pragma once

#include <cstdint>
#include <vector>

#include "diffusion/diffusion_curve.hpp"
#include "diffusion/rasterize.hpp"

namespace wisp::diffusion {

struct AntialiasOptions {
  int samples = 4;                  // n: n x n sub-samples per crossed pixel, 1 to 16
  double flatten_tolerance = 0.01;  // pixels; the rasterizer's default
};

struct AntialiasStats {
  long pixels = 0;    // pixels re-sampled (crossed by an active curve)
  long segments = 0;  // active polyline segments after flattening
};

// The area the image will be shown in, when a mask clips it later with its own anti-aliased
// coverage: closed rings (even-odd, pixel coordinates) and, per pixel, whether its centre lies
// inside them. Only sub-samples inside count, so a pixel on the region's edge takes the colour of
// its inside alone (a strand thinner than a pixel its own colour, not the solve's value at a centre
// outside it) and the clip supplies the coverage.
struct AntialiasRegion {
  std::vector<std::vector<Eigen::Vector2d>> rings;
  std::vector<std::uint8_t> centres;  // width x height, 1 inside
};

// `planes`: the solved RGB image, three planes of width x height floats, changed in place.
// `region`: optional (see AntialiasRegion). Curves are in pixel coordinates and must be valid.
AntialiasStats antialias(const std::vector<DiffusionCurve>& curves, int width, int height,
                         std::vector<float>& planes, const AntialiasRegion* region = nullptr,
                         const AntialiasOptions& options = {});

// The same, reading the solved colours from `source` and writing the re-sampled pixels into
// `planes`, which holds the same colours on entry: for a caller that keeps the plain solve (the
// renderer's warm start) beside the anti-aliased image, without a third copy of the image.
// `source` holds three planes of the pixels of `source_window` only (a solve of part of the
// image, rasterize.hpp), and stands for 0 outside it; `planes` holds three planes of the pixels of
// `planes_window` (the whole image, or the solve's window: the renderer keeps no more), and
// re-sampled pixels outside that window are not stored.
AntialiasStats antialias(const std::vector<DiffusionCurve>& curves, int width, int height,
                         const std::vector<float>& source, const PixelWindow& source_window,
                         std::vector<float>& planes, const PixelWindow& planes_window,
                         const AntialiasRegion* region = nullptr,
                         const AntialiasOptions& options = {});

}  // namespace wisp::diffusion
