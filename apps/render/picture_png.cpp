// Frames through Cairo: the layers of a FramePicture composited on an image surface.
#include <cairo.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "apps/render/picture.hpp"
#include "diffusion/blur.hpp"
#include "io/atomic_file.hpp"
#include "io/image_file.hpp"
#include "io/png_encode.hpp"
#include "vector/ink_strokes.hpp"

namespace wisp::render {
namespace {

using Surface = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;
using Context = std::unique_ptr<cairo_t, decltype(&cairo_destroy)>;

// Frames are opaque: RGB24 (Cairo writes such surfaces as RGB PNGs, without alpha); layers to
// reblur are ARGB32.
Surface make_surface(int width, int height, cairo_format_t format = CAIRO_FORMAT_RGB24) {
  Surface s(cairo_image_surface_create(format, width, height), cairo_surface_destroy);
  if (cairo_surface_status(s.get()) != CAIRO_STATUS_SUCCESS)
    throw std::runtime_error("cannot allocate a " + std::to_string(width) + "x" +
                             std::to_string(height) + " image");
  return s;
}

void set_rgb(cairo_t* cr, const Rgb& c) {
  cairo_set_source_rgb(cr, c[0], c[1], c[2]);
}

void polygon_path(cairo_t* cr, const std::vector<Eigen::Vector2d>& ring) {
  if (ring.empty()) return;
  cairo_move_to(cr, ring[0].x(), ring[0].y());
  for (size_t i = 1; i < ring.size(); ++i) cairo_line_to(cr, ring[i].x(), ring[i].y());
  cairo_close_path(cr);
}

// A Bezier path with at least one piece as the current Cairo path; `close` closes it (a filled
// region's loop).
void bezier_path(cairo_t* cr, const diffusion::BezierPath& path, bool close = false) {
  cairo_move_to(cr, path.points[0].x(), path.points[0].y());
  for (int i = 0; i < path.piece_count(); ++i) {
    const diffusion::Cubic c = path.piece(i);
    cairo_curve_to(cr, c[1].x(), c[1].y(), c[2].x(), c[2].y(), c[3].x(), c[3].y());
  }
  if (close) cairo_close_path(cr);
}

void mask_path(cairo_t* cr, const vector::HairMask& mask) {
  cairo_new_path(cr);
  for (const vector::MaskPolygon& poly : mask.polygons) {
    polygon_path(cr, poly.outer);
    for (const auto& hole : poly.holes) polygon_path(cr, hole);
  }
  cairo_set_fill_rule(cr, CAIRO_FILL_RULE_EVEN_ODD);
}

// The frame's pixel box [x0, x1) x [y0, y1) that painting the hair through `mask` reads: the
// mask's bounding box grown by the reach of Cairo's filter (a pixel at 1:1), with room to spare.
std::array<int, 4> hair_box(const vector::HairMask& mask, int width, int height) {
  double x0 = HUGE_VAL, y0 = HUGE_VAL, x1 = -HUGE_VAL, y1 = -HUGE_VAL;
  for (const vector::MaskPolygon& poly : mask.polygons)
    for (const Eigen::Vector2d& p : poly.outer) {
      x0 = std::min(x0, p.x()), y0 = std::min(y0, p.y());
      x1 = std::max(x1, p.x()), y1 = std::max(y1, p.y());
    }
  constexpr int kGrow = 4;
  const auto clamp = [](double v, int hi) { return int(std::clamp(v, 0.0, double(hi))); };
  return {clamp(std::floor(x0) - kGrow, width), clamp(std::floor(y0) - kGrow, height),
          clamp(std::ceil(x1) + kGrow, width), clamp(std::ceil(y1) + kGrow, height)};
}

// The box [x0, x1) x [y0, y1) of the hair image as an opaque Cairo surface of its size.
Surface hair_surface(const FramePicture& pic, const std::array<int, 4>& box) {
  const auto [x0, y0, x1, y1] = box;
  Surface s = make_surface(x1 - x0, y1 - y0);
  cairo_surface_flush(s.get());
  pack_hair(pic, x0, y0, x1, y1,
            reinterpret_cast<std::uint32_t*>(cairo_image_surface_get_data(s.get())),
            size_t(cairo_image_surface_get_stride(s.get())) / sizeof(std::uint32_t));
  cairo_surface_mark_dirty(s.get());
  return s;
}

// Paints the hair image through the mask (the current clip is unchanged).
void paint_hair(cairo_t* c, const FramePicture& pic) {
  const std::array<int, 4> box = hair_box(pic.mask, pic.width, pic.height);
  if (box[2] <= box[0] || box[3] <= box[1]) return;
  const Surface hair = hair_surface(pic, box);
  cairo_save(c);
  mask_path(c, pic.mask);
  cairo_clip(c);
  cairo_set_source_surface(c, hair.get(), box[0], box[1]);
  cairo_paint(c);
  cairo_restore(c);
}

// Adds the convex hull of two discs (centres a, b; radii ra, rb) as one closed subpath, turning
// the same way as every other: a fill of many such subpaths with the winding rule covers exactly
// their union, each pixel's coverage computed once.
void disc_hull(cairo_t* cr, const Eigen::Vector2d& a, double ra, const Eigen::Vector2d& b,
               double rb) {
  const Eigen::Vector2d d = b - a;
  const double len = d.norm();
  cairo_new_sub_path(cr);
  if (len <= std::abs(ra - rb)) {  // one disc holds the other
    const Eigen::Vector2d& c = ra >= rb ? a : b;
    cairo_arc(cr, c.x(), c.y(), std::max(ra, rb), 0, 2 * M_PI);
    cairo_close_path(cr);
    return;
  }
  // The outer tangents touch both circles at angles theta +- beta from the axis a -> b.
  const double theta = std::atan2(d.y(), d.x()), beta = std::acos((ra - rb) / len);
  cairo_arc(cr, a.x(), a.y(), ra, theta + beta, theta + 2 * M_PI - beta);  // round a's back
  cairo_arc(cr, b.x(), b.y(), rb, theta - beta, theta + beta);             // and b's front
  cairo_close_path(cr);
}

// A variable-width stroke as the union of the hulls of consecutive discs along its centre line,
// flattened finely enough that the union's outline is within ~0.01 px of the exact envelope.
void ink_path(cairo_t* cr, const InkStroke& ink) {
  std::vector<Eigen::Vector2d> points = ink.points;
  std::vector<double> width = ink.width;
  if (!ink.curve.points.empty()) {
    points.clear(), width.clear();
    for (const diffusion::PathSample& p : diffusion::flatten(ink.curve, 0.01)) {
      points.push_back(p.p);
      width.push_back(vector::width_at(ink.curve_width, p.t));
    }
  } else if (width.size() != points.size()) {
    return;
  }
  const size_t n = points.size();
  if (n == 1) disc_hull(cr, points[0], 0.5 * width[0], points[0], 0.5 * width[0]);
  for (size_t i = 0; i + 1 < n + (ink.closed ? 1 : 0); ++i)
    disc_hull(cr, points[i], 0.5 * width[i], points[(i + 1) % n], 0.5 * width[(i + 1) % n]);
}

// Ink in the PNG: consecutive strokes of one colour are filled as one path, so where they overlap
// (and where a stroke's own pieces do) no edge is composited twice.
void draw_ink(cairo_t* c, const std::vector<InkStroke>& strokes) {
  cairo_set_fill_rule(c, CAIRO_FILL_RULE_WINDING);
  for (size_t i = 0; i < strokes.size();) {
    cairo_new_path(c);
    size_t j = i;
    for (; j < strokes.size() && strokes[j].color == strokes[i].color; ++j) ink_path(c, strokes[j]);
    set_rgb(c, strokes[i].color);
    cairo_fill(c);
    i = j;
  }
}

// Reblurring. Rungs of 4 px and more are made on reduced images (diffusion/blur.hpp): within
// about 2/255 of the exact blur, at a cost that does not grow with the blur.
constexpr float kPyramidFrom = 4;

// Premultiplied planes (r a, g a, b a, a) in [0,1] of an ARGB32 surface, and back.
std::vector<float> surface_planes(cairo_surface_t* s) {
  cairo_surface_flush(s);
  const int w = cairo_image_surface_get_width(s), h = cairo_image_surface_get_height(s);
  const unsigned char* data = cairo_image_surface_get_data(s);
  const int stride = cairo_image_surface_get_stride(s);
  const size_t n = size_t(w) * h;
  std::vector<float> planes(4 * n);
  for (int y = 0; y < h; ++y) {
    const auto* row = reinterpret_cast<const std::uint32_t*>(data + size_t(y) * stride);
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      const std::uint32_t v = row[x];
      planes[i] = ((v >> 16) & 0xff) / 255.0f;
      planes[n + i] = ((v >> 8) & 0xff) / 255.0f;
      planes[2 * n + i] = (v & 0xff) / 255.0f;
      planes[3 * n + i] = (v >> 24) / 255.0f;
    }
  }
  return planes;
}

Surface planes_surface(const std::vector<float>& planes, int w, int h) {
  Surface s = make_surface(w, h, CAIRO_FORMAT_ARGB32);
  cairo_surface_flush(s.get());
  unsigned char* data = cairo_image_surface_get_data(s.get());
  const int stride = cairo_image_surface_get_stride(s.get());
  const size_t n = size_t(w) * h;
  const auto byte = [](float v, std::uint32_t most) {
    return std::min(most, std::uint32_t(io::unit_byte(v)));
  };
  for (int y = 0; y < h; ++y) {
    auto* row = reinterpret_cast<std::uint32_t*>(data + size_t(y) * stride);
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      const std::uint32_t a = byte(planes[3 * n + i], 255);  // premultiplied: colour <= alpha
      row[x] = a << 24 | byte(planes[i], a) << 16 | byte(planes[n + i], a) << 8 |
               byte(planes[2 * n + i], a);
    }
  }
  cairo_surface_mark_dirty(s.get());
  return s;
}

// Premultiplied planes reblurred by `sigma`, only within the box around their non-zero alpha
// that the largest sigma reaches (three sigmas): beyond it a Gaussian's tail is below 1/255.
void reblur(std::vector<float>& planes, int w, int h, const std::vector<float>& sigma) {
  const size_t n = size_t(w) * h;
  int x0 = w, y0 = h, x1 = -1, y1 = -1;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (planes[3 * n + size_t(y) * w + x] > 0)
        x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
  if (x1 < 0) return;
  const int pad = int(std::ceil(3 * *std::max_element(sigma.begin(), sigma.end())));
  x0 = std::max(0, x0 - pad), y0 = std::max(0, y0 - pad);
  x1 = std::min(w - 1, x1 + pad), y1 = std::min(h - 1, y1 + pad);
  const int cw = x1 - x0 + 1, ch = y1 - y0 + 1;
  const size_t m = size_t(cw) * ch;
  std::vector<float> crop(4 * m), crop_sigma(m);
  for (int y = 0; y < ch; ++y)
    for (int x = 0; x < cw; ++x) {
      const size_t i = size_t(y) * cw + x, j = size_t(y + y0) * w + (x + x0);
      for (int c = 0; c < 4; ++c) crop[c * m + i] = planes[c * n + j];
      crop_sigma[i] = sigma[j];
    }
  diffusion::BlurOptions options;
  options.pyramid_from = kPyramidFrom;
  crop = diffusion::spatially_varying_blur(crop, 4, cw, ch, crop_sigma, options);
  for (int y = 0; y < ch; ++y)
    for (int x = 0; x < cw; ++x)
      for (int c = 0; c < 4; ++c)
        planes[c * n + size_t(y + y0) * w + (x + x0)] = crop[c * m + size_t(y) * cw + x];
}

// The ink strokes alone, reblurred like the hair under them.
Surface blurred_ink(const FramePicture& pic) {
  Surface layer = make_surface(pic.width, pic.height, CAIRO_FORMAT_ARGB32);
  {
    Context cr(cairo_create(layer.get()), cairo_destroy);
    draw_ink(cr.get(), pic.ink);
  }
  std::vector<float> planes = surface_planes(layer.get());
  reblur(planes, pic.width, pic.height, pic.blur);
  return planes_surface(planes, pic.width, pic.height);
}

void paint_layer(cairo_t* c, cairo_surface_t* layer) {
  cairo_set_source_surface(c, layer, 0, 0);
  cairo_paint(c);
}

Surface draw(const FramePicture& pic) {
  Surface surface = make_surface(pic.width, pic.height);
  Context cr(cairo_create(surface.get()), cairo_destroy);
  cairo_t* c = cr.get();
  set_rgb(c, pic.background);
  cairo_paint(c);
  // Body: one fill per tone region, all its loops in one path (no interior edge is drawn).
  cairo_set_fill_rule(c, CAIRO_FILL_RULE_WINDING);
  for (const BodyPath& region : pic.body) {
    cairo_new_path(c);
    for (const auto& loop : region.loops)
      if (loop.size() >= 4) bezier_path(c, {loop}, true);
    set_rgb(c, region.color);
    cairo_fill(c);
  }
  draw_ink(c, pic.face);  // on the head, under the hair
  if (!pic.blurred_hair.empty()) {
    paint_layer(c, planes_surface(pic.blurred_hair, pic.width, pic.height).get());
    if (!pic.ink.empty()) paint_layer(c, blurred_ink(pic).get());
    cairo_surface_flush(surface.get());
    return surface;
  }
  if (!pic.hair.planes.empty() && !pic.mask.polygons.empty()) paint_hair(c, pic);
  draw_ink(c, pic.hatching);
  // Fur: one fill per tuft, its strands in one path, so they do not darken where they overlap.
  for (const vector::FurTuft& tuft : pic.fur) {
    cairo_new_path(c);
    for (const auto& loop : tuft.loops)
      if (loop.size() >= 4) bezier_path(c, {loop}, true);
    cairo_set_source_rgba(c, tuft.color[0], tuft.color[1], tuft.color[2], tuft.opacity);
    cairo_fill(c);
  }
  draw_ink(c, pic.ink);
  cairo_surface_flush(surface.get());
  return surface;
}

}  // namespace

void pack_hair(const FramePicture& pic, int x0, int y0, int x1, int y1, std::uint32_t* out,
               std::size_t stride) {
  const diffusion::PixelWindow& w = pic.hair_window;
  const diffusion::Image& img = pic.hair;
  if (img.width != w.width || img.height != w.height ||
      img.planes.size() != 3 * size_t(img.width) * img.height)
    throw std::logic_error("pack_hair: the hair image is not its window's size");
  const std::uint32_t black = 0xff000000u;  // io::pack_rgb's word for 0, 0, 0
  // The part of the box inside the window, [wx0, wx1) x [wy0, wy1), in the frame's pixels.
  const int wx0 = std::clamp(w.x, x0, x1), wx1 = std::clamp(w.x + w.width, wx0, x1);
  const int wy0 = std::clamp(w.y, y0, y1), wy1 = std::clamp(w.y + w.height, wy0, y1);
  if (wx0 < wx1 && wy0 < wy1)
    io::pack_rgb_box(img, wx0 - w.x, wy0 - w.y, wx1 - w.x, wy1 - w.y,
                     out + size_t(wy0 - y0) * stride + (wx0 - x0), stride);
  for (int y = y0; y < y1; ++y) {
    std::uint32_t* row = out + size_t(y - y0) * stride;
    if (y < wy0 || y >= wy1 || wx0 == wx1) {
      std::fill(row, row + (x1 - x0), black);
      continue;
    }
    std::fill(row, row + (wx0 - x0), black);
    std::fill(row + (wx1 - x0), row + (x1 - x0), black);
  }
}

std::vector<std::uint8_t> rasterize_frame(const FramePicture& pic) {
  const Surface s = draw(pic);
  const unsigned char* data = cairo_image_surface_get_data(s.get());
  const int stride = cairo_image_surface_get_stride(s.get());
  std::vector<std::uint8_t> rgba(size_t(pic.width) * pic.height * 4);
  for (int y = 0; y < pic.height; ++y) {
    const auto* row = reinterpret_cast<const std::uint32_t*>(data + size_t(y) * stride);
    for (int x = 0; x < pic.width; ++x) {
      const std::uint32_t v = row[x];
      std::uint8_t* out = &rgba[(size_t(y) * pic.width + x) * 4];
      out[0] = (v >> 16) & 0xff;
      out[1] = (v >> 8) & 0xff;
      out[2] = v & 0xff;
      out[3] = 255;
    }
  }
  return rgba;
}

std::vector<std::uint8_t> rasterize_mask(const vector::HairMask& mask, int width, int height) {
  Surface s(cairo_image_surface_create(CAIRO_FORMAT_A8, width, height), cairo_surface_destroy);
  Context cr(cairo_create(s.get()), cairo_destroy);
  mask_path(cr.get(), mask);
  cairo_set_source_rgba(cr.get(), 0, 0, 0, 1);
  cairo_fill(cr.get());
  cairo_surface_flush(s.get());
  const unsigned char* data = cairo_image_surface_get_data(s.get());
  const int stride = cairo_image_surface_get_stride(s.get());
  std::vector<std::uint8_t> out(size_t(width) * height);
  for (int y = 0; y < height; ++y)
    std::copy(data + size_t(y) * stride, data + size_t(y) * stride + width,
              &out[size_t(y) * width]);
  return out;
}

std::vector<float> reblur_hair(const FramePicture& pic) {
  if (pic.blur.size() != size_t(pic.width) * pic.height)
    throw std::logic_error("reblur_hair: the picture has no blur map of its size");
  Surface layer = make_surface(pic.width, pic.height, CAIRO_FORMAT_ARGB32);
  if (!pic.hair.planes.empty() && !pic.mask.polygons.empty()) {
    Context cr(cairo_create(layer.get()), cairo_destroy);
    paint_hair(cr.get(), pic);
  }
  std::vector<float> planes = surface_planes(layer.get());
  reblur(planes, pic.width, pic.height, pic.blur);
  return planes;
}

std::vector<std::uint8_t> hair_matte(const FramePicture& pic) {
  if (pic.blurred_hair.empty()) return rasterize_mask(pic.mask, pic.width, pic.height);
  const size_t n = size_t(pic.width) * pic.height;
  std::vector<std::uint8_t> coverage(n);
  for (size_t i = 0; i < n; ++i) coverage[i] = io::unit_byte(pic.blurred_hair[3 * n + i]);
  return coverage;
}

void write_mask_png(const FramePicture& pic, const std::filesystem::path& path) {
  const std::vector<std::uint8_t> coverage = hair_matte(pic);
  io::write_png_fast(path, {coverage.data(), pic.width, pic.height, 1, size_t(pic.width)});
}

void write_mask_png(const vector::HairMask& mask, int width, int height,
                    const std::filesystem::path& path) {
  const std::vector<std::uint8_t> coverage = rasterize_mask(mask, width, height);
  io::write_png_fast(path, {coverage.data(), width, height, 1, size_t(width)});
}

void write_frame_png(const FramePicture& pic, const std::filesystem::path& path) {
  const Surface s = draw(pic);
  // Cairo's RGB24 pixels are native-endian 0x00RRGGBB words, which the encoder takes as they are.
  io::write_png_fast(path, {cairo_image_surface_get_data(s.get()), pic.width, pic.height, 3,
                            size_t(cairo_image_surface_get_stride(s.get())), true});
}

}  // namespace wisp::render
