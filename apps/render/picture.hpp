// A finished frame as layers of plain geometry, in pixels, back to front: background, body
// (skin tones, then the face's lines), the hair base, the smooth-shaded hair clipped by the hair
// mask (the base is part of it), highlights, hatch strokes, fur tufts, ink strokes. With a blur map
// the hair, its mask's edge and the ink are reblurred (Orzan's reblur, vector/hair_blur.hpp); the
// body stays sharp. The same picture is written as a PNG (rasterised by Cairo, anti-aliased) and as
// an SVG (real paths, the shading embedded as an image clipped by the silhouette, or flat per-wisp
// gradients) whose layers are Inkscape layers (svg_layers()); frames' SVGs become one animated SVG
// in apps/render/svg_animation.hpp.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "diffusion/bezier.hpp"
#include "diffusion/rasterize.hpp"
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
  std::string kind;  // what it draws, for its SVG id: "silhouette", "occlusion", "brow", ...
  std::vector<Eigen::Vector2d> points;
  std::vector<double> width;
  Rgb color = Rgb::Zero();
  bool closed = false;
  // The stroke as a Bezier path with its full width as (s, px) stops over the path parameter s,
  // linear in between. When set, PNG and SVG draw this and `points`/`width` are
  // its flattening, for tools that want polylines.
  diffusion::BezierPath curve;
  std::vector<std::pair<double, double>> curve_width;
};

// A Bezier path with its full width as (s, px) stops as a stroke in `color`, with its flattening
// (for tools that draw polylines) at the cubics' ends and thirds.
InkStroke ink_stroke(const diffusion::BezierPath& path,
                     const std::vector<std::pair<double, double>>& width, const Rgb& color);

// A variable-width Bezier stroke as constant-width stroked paths, as the SVG draws it (one <path>
// with stroke-width each, an editable stroke): the cubics are split (de Casteljau, exact geometry)
// wherever the width, rounded to a multiple of `step` px, changes, and consecutive pieces of the
// same rounded width form one path, stroked with round caps and joins. Widths are thus within
// step/2 of the exact profile; pieces rounding to 0 are left out. The PNG fills the exact width
// profile instead (picture_png.cpp): viewers composite the pieces' overlapping caps twice.
struct InkPiece : diffusion::BezierPath {
  double width = 0;
};
std::vector<InkPiece> ink_pieces(const InkStroke& stroke, double step = 0.25);

// A wisp for flat SVGs: where it is in front, filled with a linear gradient along the wisp from
// root to tip.
struct FlatRegion {
  int wisp = -1;  // vector::Wisp::strand, for its SVG id
  vector::HairMask area;
  Eigen::Vector2d from{0, 0}, to{0, 0};
  std::vector<std::pair<double, Rgb>> stops;  // offset in [0,1], colour
};

// A stylised highlight (vector/highlights.hpp) for flat SVGs, where the gradients along the wisps
// do not draw it: its outline, filled with its colour where its wisp is in front (the wisp's
// FlatRegion). PNGs and embedded SVGs have it in the hair image already.
struct Highlight {
  int wisp = -1;  // vector::Wisp::strand
  std::vector<Eigen::Vector2d> ring;
  Rgb color = Rgb::Zero();
};

// A wisp's closed outline, for the hidden debug layer of SVGs.
struct WispOutline {
  int wisp = -1;  // vector::Wisp::strand
  diffusion::BezierPath path;
};

struct FramePicture {
  int width = 0, height = 0;
  Rgb background{1, 1, 1};
  std::vector<BodyPath> body;   // back to front
  std::vector<InkStroke> face;  // facial features, drawn on the body (under the hair)
  // The smooth shading at the frame's resolution, kept for the pixels of hair_window only (the
  // solve's window, which holds every curve and so the mask): hair.width x hair.height is
  // hair_window's size, and the frame is black outside it. Empty: no hair.
  diffusion::Image hair;
  diffusion::PixelWindow hair_window;
  vector::HairMask mask;  // where the hair image shows
  // Where the hair base shows (inside the mask) and its colour: its own layer in SVGs, under the
  // hair (in PNGs the hair image covers it).
  vector::HairMask base;
  Rgb base_color = Rgb::Zero();
  // Hatch strokes in the shadows (vector/hatching.hpp): over the hair and the body, under the ink.
  std::vector<InkStroke> hatching;
  // Fur tufts (vector/fur.hpp), back to front, over the hair and under the ink: each one filled
  // path in its colour at its opacity.
  std::vector<vector::FurTuft> fur;
  std::vector<InkStroke> ink;  // on top of everything
  // The blur map (vector/hair_blur.hpp): a Gaussian sigma in pixels per pixel of the frame, by
  // which the hair, its mask's edge and the ink over it are reblurred; empty: all sharp.
  std::vector<float> blur;
  // With a blur map: the hair through its mask, reblurred (reblur_hair), as premultiplied planes
  // (r a, g a, b a, a) of width*height floats; drawn instead of `hair` clipped by `mask`.
  std::vector<float> blurred_hair;
  // SVG only: the wisp outlines, in a hidden debug layer, and the per-wisp regions and highlights
  // of --svg-style flat.
  std::vector<WispOutline> outlines;
  std::vector<FlatRegion> flat;
  std::vector<Highlight> highlights;  // flat SVGs only
};

// 8-bit RGBA, row-major, not premultiplied (alpha is 255 everywhere: frames are opaque).
std::vector<std::uint8_t> rasterize_frame(const FramePicture& picture);

// Only the anti-aliased hair mask, as coverage in [0,255] per pixel (row-major).
std::vector<std::uint8_t> rasterize_mask(const vector::HairMask& mask, int width, int height);

// The hair image through the mask's coverage, reblurred by the picture's blur map (which must
// be there): premultiplied planes as FramePicture::blurred_hair, so the mask's edge softens
// where the map blurs instead of cutting the blurred hair. Only the box the blur can reach
// around the mask is blurred.
std::vector<float> reblur_hair(const FramePicture& picture);

// The hair image's pixels in the frame's box [x0, x1) x [y0, y1) as 0xffRRGGBB words
// (io::pack_rgb), rows `stride` words apart; black outside the picture's hair_window.
void pack_hair(const FramePicture& picture, int x0, int y0, int x1, int y1, std::uint32_t* out,
               std::size_t stride);

// Written atomically; errors name the file.
void write_frame_png(const FramePicture& picture, const std::filesystem::path& path);
// The anti-aliased hair mask as an 8-bit grey PNG (a matte for compositing elsewhere).
void write_mask_png(const vector::HairMask& mask, int width, int height,
                    const std::filesystem::path& path);
// The picture's hair matte as coverage in [0,255] per pixel: its mask's (rasterize_mask), or
// with a blur map the reblurred hair's alpha. And as an 8-bit grey PNG.
std::vector<std::uint8_t> hair_matte(const FramePicture& picture);
void write_mask_png(const FramePicture& picture, const std::filesystem::path& path);

// Embedded: the shading as an image clipped by the silhouette; Flat: a gradient path per
// visible wisp region.
enum class SvgStyle { Embedded, Flat };
constexpr std::array<sim::Choice<SvgStyle>, 2> choices(SvgStyle) {
  return {{{"embedded", SvgStyle::Embedded}, {"flat", SvgStyle::Flat}}};
}

// The layers of every SVG, back to front, as Inkscape layers (<g inkscape:groupmode="layer">) with
// these ids and labels; `hidden` ones start hidden (debug aids). Each has its writer in
// picture_svg.cpp; a new layer is one more entry there.
struct SvgLayer {
  const char* id;
  const char* label;
  bool hidden = false;
};

// The layers' ids, back to front (for tools and tests).
std::vector<SvgLayer> svg_layers();

// Coordinates are written with as many decimals as the picture's size needs: a rounding error of at
// most 1/65536 of its larger side (a 16-bit grid over the frame): 2 decimals at 512 to 2048 px.
int svg_decimals(int width, int height);

void write_frame_svg(const FramePicture& picture, const std::filesystem::path& path,
                     SvgStyle style);
std::string format_frame_svg(const FramePicture& picture, SvgStyle style);

}  // namespace wisp::render
