// A finished frame as layers of plain geometry, in pixels, back to front: background, body
// (skin tones, then the face's lines), the hair base, the smooth-shaded hair clipped by the hair
// mask (the base is part of it), fur tufts, ink strokes. The same picture is written as
// a PNG (rasterised by Cairo, anti-aliased) and as an SVG (real paths, the shading embedded as an
// image clipped by the silhouette, or flat per-wisp gradients).
#pragma once

#include <Eigen/Core>
#include <array>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "diffusion/bezier.hpp"
#include "diffusion/render.hpp"
#include "sim/choices.hpp"
#include "vector/arrangement.hpp"
#include "vector/fur.hpp"

namespace wisp::render {

using Rgb = Eigen::Vector3f;  // [0,1]

// A region of one flat skin tone on one body surface (apps/render/body_paths.hpp): closed cubic
// Bezier loops (3k+1 control points each, the last equal to the first), filled together with the
// nonzero winding rule (holes run the other way round).
struct BodyPath {
  std::vector<std::vector<Eigen::Vector2d>> loops;
  Rgb color = Rgb::Zero();
  int part = 0;         // sim::BodyPart
  bool shadow = false;  // the shadow tone, drawn over its surface's lit fill
};

// A variable-width stroke: the polyline's width at each point, in pixels.
struct InkStroke {
  std::vector<Eigen::Vector2d> points;
  std::vector<double> width;
  Rgb color = Rgb::Zero();
  bool closed = false;
  // The stroke as a Bezier path with its full width as (s, px) stops over the path parameter s,
  // linear in between. When set, PNG and SVG draw this (see ink_pieces) and `points`/`width` are
  // its flattening, for tools that want polylines.
  diffusion::BezierPath curve;
  std::vector<std::pair<double, double>> curve_width;
};

// A variable-width Bezier stroke as constant-width stroked paths, drawn the same way in the PNG
// (Cairo) and the SVG (one <path> with stroke-width each; rsvg is Cairo, browsers stroke alike):
// the cubics are split (de Casteljau, exact geometry) wherever the width, rounded to a multiple
// of `step` px, changes, and consecutive pieces of the same rounded width form one path, stroked
// with round caps and joins. Widths are thus within step/2 of the exact profile; pieces rounding
// to 0 are left out. A filled outline of offset curves would follow the width exactly but needs
// offset approximations that fold on tight bends; stroking keeps every path a real stroke that
// editors understand.
struct InkPiece : diffusion::BezierPath {
  double width = 0;
};
std::vector<InkPiece> ink_pieces(const InkStroke& stroke, double step = 0.25);

// A wisp for flat SVGs: where it is in front, filled with a linear gradient along the wisp from
// root to tip.
struct FlatRegion {
  vector::HairMask area;
  Eigen::Vector2d from{0, 0}, to{0, 0};
  std::vector<std::pair<double, Rgb>> stops;  // offset in [0,1], colour
};

struct FramePicture {
  int width = 0, height = 0;
  Rgb background{1, 1, 1};
  std::vector<BodyPath> body;   // back to front
  std::vector<InkStroke> face;  // facial features, drawn on the body (under the hair)
  diffusion::Image hair;        // full-frame smooth shading (may be empty: no hair)
  vector::HairMask mask;        // where the hair image shows
  // Where the hair base shows (inside the mask) and its colour: its own layer in SVGs, under the
  // hair (in PNGs the hair image covers it).
  vector::HairMask base;
  Rgb base_color = Rgb::Zero();
  // Fur tufts (vector/fur.hpp), back to front, over the hair and under the ink: each one filled
  // path in its colour at its opacity.
  std::vector<vector::FurTuft> fur;
  std::vector<InkStroke> ink;  // on top of everything
  // SVG only: the wisp outlines, in a hidden debug group, and the per-wisp regions of
  // --svg-style flat.
  std::vector<diffusion::BezierPath> outlines;
  std::vector<FlatRegion> flat;
};

// 8-bit RGBA, row-major, not premultiplied (alpha is 255 everywhere: frames are opaque).
std::vector<std::uint8_t> rasterize_frame(const FramePicture& picture);

// Only the anti-aliased hair mask, as coverage in [0,255] per pixel (row-major).
std::vector<std::uint8_t> rasterize_mask(const vector::HairMask& mask, int width, int height);

// Written atomically; errors name the file.
void write_frame_png(const FramePicture& picture, const std::filesystem::path& path);
// The anti-aliased hair mask as an 8-bit grey PNG (a matte for compositing elsewhere).
void write_mask_png(const vector::HairMask& mask, int width, int height,
                    const std::filesystem::path& path);

// Embedded: the shading as an image clipped by the silhouette; Flat: a gradient path per
// visible wisp region.
enum class SvgStyle { Embedded, Flat };
constexpr std::array<sim::Choice<SvgStyle>, 2> choices(SvgStyle) {
  return {{{"embedded", SvgStyle::Embedded}, {"flat", SvgStyle::Flat}}};
}
void write_frame_svg(const FramePicture& picture, const std::filesystem::path& path,
                     SvgStyle style);
std::string format_frame_svg(const FramePicture& picture, SvgStyle style);

}  // namespace wisp::render
