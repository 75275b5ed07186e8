// Frames through Cairo: the layers of a FramePicture composited on an image surface.
#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "apps/render/picture.hpp"
#include "io/atomic_file.hpp"
#include "io/png_encode.hpp"

namespace wisp::render {
namespace {

using Surface = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;
using Context = std::unique_ptr<cairo_t, decltype(&cairo_destroy)>;

// Frames are opaque: RGB24 (Cairo writes such surfaces as RGB PNGs, without alpha).
Surface make_surface(int width, int height) {
  Surface s(cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height), cairo_surface_destroy);
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

// The hair image as an opaque Cairo surface.
Surface hair_surface(const diffusion::Image& img) {
  Surface s = make_surface(img.width, img.height);
  cairo_surface_flush(s.get());
  unsigned char* data = cairo_image_surface_get_data(s.get());
  const int stride = cairo_image_surface_get_stride(s.get());
  const size_t n = size_t(img.width) * size_t(img.height);
  const auto byte = [](float v) {
    return std::uint32_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255));
  };
  for (int y = 0; y < img.height; ++y) {
    auto* row = reinterpret_cast<std::uint32_t*>(data + size_t(y) * stride);
    for (int x = 0; x < img.width; ++x) {
      const size_t i = size_t(y) * img.width + x;
      row[x] = 0xff000000u | byte(img.planes[i]) << 16 | byte(img.planes[n + i]) << 8 |
               byte(img.planes[2 * n + i]);
    }
  }
  cairo_surface_mark_dirty(s.get());
  return s;
}

// A variable-width stroke as a filled outline: segments with per-end widths plus round joins.
void ink_path(cairo_t* cr, const InkStroke& ink) {
  const size_t n = ink.points.size();
  for (size_t i = 0; i + 1 < n + (ink.closed ? 1 : 0); ++i) {
    const Eigen::Vector2d a = ink.points[i], b = ink.points[(i + 1) % n];
    const double wa = 0.5 * ink.width[i], wb = 0.5 * ink.width[(i + 1) % n];
    const Eigen::Vector2d d = b - a;
    if (d.norm() < 1e-9) continue;
    const Eigen::Vector2d nrm = Eigen::Vector2d(-d.y(), d.x()).normalized();
    cairo_move_to(cr, a.x() + nrm.x() * wa, a.y() + nrm.y() * wa);
    cairo_line_to(cr, b.x() + nrm.x() * wb, b.y() + nrm.y() * wb);
    cairo_line_to(cr, b.x() - nrm.x() * wb, b.y() - nrm.y() * wb);
    cairo_line_to(cr, a.x() - nrm.x() * wa, a.y() - nrm.y() * wa);
    cairo_close_path(cr);
  }
  for (size_t i = 0; i < n; ++i) {
    cairo_new_sub_path(cr);
    cairo_arc(cr, ink.points[i].x(), ink.points[i].y(), 0.5 * ink.width[i], 0, 2 * M_PI);
  }
}

void draw_ink(cairo_t* c, const std::vector<InkStroke>& strokes) {
  cairo_set_fill_rule(c, CAIRO_FILL_RULE_WINDING);
  cairo_set_line_cap(c, CAIRO_LINE_CAP_ROUND);
  cairo_set_line_join(c, CAIRO_LINE_JOIN_ROUND);
  for (const InkStroke& ink : strokes) {
    if (!ink.curve.points.empty()) {
      set_rgb(c, ink.color);
      for (const InkPiece& piece : ink_pieces(ink)) {
        cairo_new_path(c);
        bezier_path(c, piece);
        cairo_set_line_width(c, piece.width);
        cairo_stroke(c);
      }
      continue;
    }
    if (ink.points.size() < 2 || ink.width.size() != ink.points.size()) continue;
    cairo_new_path(c);
    ink_path(c, ink);
    set_rgb(c, ink.color);
    cairo_fill(c);
  }
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
  if (!pic.hair.planes.empty() && !pic.mask.polygons.empty()) {
    Surface hair = hair_surface(pic.hair);
    cairo_save(c);
    mask_path(c, pic.mask);
    cairo_clip(c);
    cairo_scale(c, double(pic.width) / pic.hair.width, double(pic.height) / pic.hair.height);
    cairo_set_source_surface(c, hair.get(), 0, 0);
    cairo_paint(c);
    cairo_restore(c);
  }
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

void write_mask_png(const vector::HairMask& mask, int width, int height,
                    const std::filesystem::path& path) {
  const std::vector<std::uint8_t> coverage = rasterize_mask(mask, width, height);
  io::write_png_fast(path, {coverage.data(), width, height, 1, size_t(width)});
}

void write_frame_png(const FramePicture& pic, const std::filesystem::path& path) {
  const Surface s = draw(pic);
  // Cairo's RGB24 pixels are native-endian 0x00RRGGBB words; the PNG wants RGB bytes.
  const unsigned char* data = cairo_image_surface_get_data(s.get());
  const int stride = cairo_image_surface_get_stride(s.get());
  std::vector<std::uint8_t> rgb(size_t(pic.width) * pic.height * 3);
  for (int y = 0; y < pic.height; ++y) {
    const auto* row = reinterpret_cast<const std::uint32_t*>(data + size_t(y) * stride);
    std::uint8_t* out = &rgb[size_t(y) * pic.width * 3];
    for (int x = 0; x < pic.width; ++x) {
      out[3 * x] = (row[x] >> 16) & 0xff;
      out[3 * x + 1] = (row[x] >> 8) & 0xff;
      out[3 * x + 2] = row[x] & 0xff;
    }
  }
  io::write_png_fast(path, {rgb.data(), pic.width, pic.height, 3, size_t(pic.width) * 3});
}

}  // namespace wisp::render
