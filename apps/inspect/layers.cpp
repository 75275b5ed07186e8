// Drawing the inspector's layers with Cairo (see layers.hpp).
#include "apps/inspect/layers.hpp"

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <stdexcept>

#include "vector/polygon.hpp"

namespace wisp::inspect {
namespace {

using Surface = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;
using Context = std::unique_ptr<cairo_t, decltype(&cairo_destroy)>;
using Vec2 = Eigen::Vector2d;

const std::array<LayerInfo, kLayerCount> kLayers{{
    {Layer::Image, "image", 'i', true, "finished frame"},
    {Layer::Faces, "faces", 'f', true, "faces, coloured by front-most wisp"},
    {Layer::Coverage, "coverage", 'c', true, "coverage count (heat map)"},
    {Layer::Mask, "mask", 'm', true, "hair mask"},
    {Layer::Constraints, "constraints", 'p', true, "constraint pixels of the solve"},
    {Layer::Residual, "residual", 'r', true, "solver residual, log scale ([ ] step)"},
    {Layer::Outlines, "outlines", 'o', false, "wisp outlines by wisp id"},
    {Layer::Visibility, "visibility", 'v', false, "visible (green) / hidden (red) pieces, seams"},
    {Layer::Curves, "curves", 'b', false, "centre curves and control points"},
    {Layer::Vertices, "vertices", 'x', false, "intersection vertices"},
    {Layer::Ink, "ink", 'k', false, "ink strokes (silhouette, occlusion)"},
}};

void set_rgb(cairo_t* cr, const Rgb8& c) {
  cairo_set_source_rgb(cr, c[0] / 255.0, c[1] / 255.0, c[2] / 255.0);
}

std::uint32_t argb(const Rgb8& c) {
  return 0xff000000u | std::uint32_t(c[0]) << 16 | std::uint32_t(c[1]) << 8 | c[2];
}

std::uint8_t to_byte(float v) {
  return std::uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255));
}

Rgb8 hsv(double h, double s, double v) {
  h = (h - std::floor(h)) * 6;
  const int i = int(h) % 6;
  const double f = h - std::floor(h), p = v * (1 - s), q = v * (1 - s * f),
               t = v * (1 - s * (1 - f));
  double r = v, g = t, b = p;
  switch (i) {
    case 1:
      r = q, g = v, b = p;
      break;
    case 2:
      r = p, g = v, b = t;
      break;
    case 3:
      r = p, g = q, b = v;
      break;
    case 4:
      r = t, g = p, b = v;
      break;
    case 5:
      r = v, g = p, b = q;
      break;
    default:
      break;
  }
  const auto byte = [](double x) {
    return std::uint8_t(std::lround(std::clamp(x, 0.0, 1.0) * 255));
  };
  return {byte(r), byte(g), byte(b)};
}

// A frame-sized ARGB32 raster (premultiplied; 0 is transparent) painted through the view:
// magnified without smoothing.
void paint_raster(cairo_t* cr, std::vector<std::uint32_t>& pixels, int width, int height,
                  const ViewTransform& view, double opacity, int x = 0, int y = 0) {
  Surface s(cairo_image_surface_create_for_data(reinterpret_cast<unsigned char*>(pixels.data()),
                                                CAIRO_FORMAT_ARGB32, width, height, width * 4),
            cairo_surface_destroy);
  cairo_save(cr);
  cairo_translate(cr, view.offset.x(), view.offset.y());
  cairo_scale(cr, view.zoom, view.zoom);
  cairo_set_source_surface(cr, s.get(), x, y);
  cairo_pattern_set_filter(cairo_get_source(cr), CAIRO_FILTER_NEAREST);
  cairo_paint_with_alpha(cr, opacity);
  cairo_restore(cr);
}

// Covered faces inside the view, each filled (centre-sampled, not anti-aliased) with color(face,
// its number among those faces), on the canvas under the view.
template <class ColorOf>
void paint_faces(cairo_t* cr, const vector::ArrangementView& view, const ViewTransform& t,
                 double opacity, ColorOf color) {
  cairo_surface_t* target = cairo_get_target(cr);
  const int width = cairo_image_surface_get_width(target);
  const int height = cairo_image_surface_get_height(target);
  std::vector<std::uint32_t> pixels(size_t(width) * height, 0);
  std::vector<std::vector<Vec2>> rings;
  int number = 0;
  for (const vector::ViewFace& f : view.faces) {
    if ((f.front < 0 && !f.base) || !f.in_view || f.outer.empty()) continue;
    rings.assign(1, f.outer);
    rings.insert(rings.end(), f.holes.begin(), f.holes.end());
    for (auto& r : rings)
      for (Vec2& p : r) p = t.to_canvas(p);
    const Rgb8 c = color(f, number++);
    vector::fill_centres(pixels, width, height, rings,
                         0xff000000u | std::uint32_t(c[0]) << 16 | std::uint32_t(c[1]) << 8 | c[2]);
  }
  paint_raster(cr, pixels, width, height, ViewTransform{}, opacity);
}

// Line layers draw in canvas pixels: points go through the view, widths do not.
struct Pen {
  cairo_t* cr;
  const ViewTransform& view;

  void move(const Vec2& p) const {
    const Vec2 q = view.to_canvas(p);
    cairo_move_to(cr, q.x(), q.y());
  }
  void line(const Vec2& p) const {
    const Vec2 q = view.to_canvas(p);
    cairo_line_to(cr, q.x(), q.y());
  }
  void curve(const Vec2& a, const Vec2& b, const Vec2& c) const {
    const Vec2 qa = view.to_canvas(a), qb = view.to_canvas(b), qc = view.to_canvas(c);
    cairo_curve_to(cr, qa.x(), qa.y(), qb.x(), qb.y(), qc.x(), qc.y());
  }
  void bezier(const diffusion::BezierPath& path) const {
    for (int i = 0; i < path.piece_count(); ++i) {
      const diffusion::Cubic c = path.piece(i);
      if (i == 0) move(c[0]);
      curve(c[1], c[2], c[3]);
    }
  }
  void polyline(const std::vector<Vec2>& points, bool closed) const {
    if (points.empty()) return;
    move(points[0]);
    for (size_t i = 1; i < points.size(); ++i) line(points[i]);
    if (closed) cairo_close_path(cr);
  }
  void stroke(const Rgb8& color, double width) const {
    set_rgb(cr, color);
    cairo_set_line_width(cr, width);
    cairo_stroke(cr);
  }
  void dot(const Vec2& p, double radius) const {
    const Vec2 q = view.to_canvas(p);
    cairo_new_sub_path(cr);
    cairo_arc(cr, q.x(), q.y(), radius, 0, 2 * M_PI);
  }
  void square(const Vec2& p, double half) const {
    const Vec2 q = view.to_canvas(p);
    cairo_rectangle(cr, q.x() - half, q.y() - half, 2 * half, 2 * half);
  }
};

void draw_image(cairo_t* cr, const InspectFrame& f, const ViewTransform& t, double opacity) {
  const int W = f.width(), H = f.height();
  std::vector<std::uint32_t> px(size_t(W) * H);
  for (size_t i = 0; i < px.size(); ++i)
    px[i] = argb({f.image[4 * i], f.image[4 * i + 1], f.image[4 * i + 2]});
  paint_raster(cr, px, W, H, t, opacity);
}

void draw_mask(cairo_t* cr, const InspectFrame& f, const ViewTransform& t, double opacity) {
  std::vector<std::uint32_t> px(f.mask.size());
  for (size_t i = 0; i < px.size(); ++i) px[i] = argb({f.mask[i], f.mask[i], f.mask[i]});
  paint_raster(cr, px, f.width(), f.height(), t, opacity);
}

void draw_constraints(cairo_t* cr, const InspectFrame& f, const ViewTransform& t, double opacity,
                      cv::Size canvas) {
  // The problem covers the solve's window (FrameResult::window).
  const diffusion::Problem& p = f.result.problem;
  const diffusion::PixelWindow& win = f.result.window;
  if (p.width != win.width || p.height != win.height || p.pixel_count() == 0) return;
  const size_t n = p.pixel_count();
  std::vector<std::uint32_t> px(n, 0);
  for (size_t i = 0; i < n; ++i)
    if (p.fixed[i] || p.anchor_weight[i] > 0)  // anchored: in the anchor value (problem.hpp)
      px[i] = argb({to_byte(p.value[i]), to_byte(p.value[n + i]), to_byte(p.value[2 * n + i])});
  paint_raster(cr, px, p.width, p.height, t, opacity, win.x, win.y);

  // Cut links (curves cross them: no colour flows there) as the pixel borders they close, once
  // pixels are big enough to see them.
  if (t.zoom < 6) return;
  const Vec2 lo = t.to_frame({0, 0}),
             hi = t.to_frame({double(canvas.width), double(canvas.height)});
  const int x0 = std::max(0, int(std::floor(lo.x())) - 1 - win.x),
            y0 = std::max(0, int(std::floor(lo.y())) - 1 - win.y);
  const int x1 = std::min(p.width, int(std::ceil(hi.x())) + 1 - win.x);
  const int y1 = std::min(p.height, int(std::ceil(hi.y())) + 1 - win.y);
  const Pen pen{cr, t};
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const std::uint8_t l = p.links[p.index(x, y)];
      const double X = win.x + x, Y = win.y + y;
      if (x + 1 < p.width && !(l & diffusion::kOpenEast)) {
        pen.move({X + 1, Y});
        pen.line({X + 1, Y + 1});
      }
      if (y + 1 < p.height && !(l & diffusion::kOpenSouth)) {
        pen.move({X, Y + 1});
        pen.line({X + 1, Y + 1});
      }
    }
  pen.stroke(kCutLinkColor, 2.0);
}

void draw_residual(cairo_t* cr, const InspectFrame& f, const LayerSet& layers,
                   const ViewTransform& t, double opacity) {
  const int step = residual_step(f, layers);
  if (step < 0) return;
  const std::vector<float>& r = f.residual[step];
  const diffusion::PixelWindow& win = f.result.window;  // the residual covers it
  if (r.size() != win.pixel_count() || r.empty()) return;
  std::vector<std::uint32_t> px(r.size(), 0);
  for (size_t i = 0; i < r.size(); ++i)
    if (r[i] > 0) px[i] = argb(residual_color(r[i]));
  paint_raster(cr, px, win.width, win.height, t, opacity, win.x, win.y);
}

void draw_outlines(const Pen& pen, const InspectFrame& f) {
  const auto& wisps = f.result.wisps;
  for (size_t w = 0; w < wisps.size(); ++w) {
    cairo_new_path(pen.cr);
    pen.bezier(wisps[w].outline);
    pen.stroke(wisp_color(int(w)), 1.25);
  }
}

void draw_visibility(const Pen& pen, const InspectFrame& f) {
  const auto& edges = f.result.arrangement.view.edges;
  const auto draw_if = [&](const auto& wanted) {
    cairo_new_path(pen.cr);
    for (const vector::ViewEdge& e : edges)
      if (wanted(e)) {
        pen.move(e.a);
        pen.line(e.b);
      }
  };
  const auto outline = [](const vector::ViewEdge& e, bool visible) {
    bool any = false, shown = false;
    for (const vector::ViewEdgeSource& s : e.sources) {
      any |= s.wisp >= 0;
      shown |= s.wisp >= 0 && s.visible;
    }
    return any && shown == visible;
  };
  // Hidden pieces, then the depth seams (vector/depth_seams.hpp: edges along no outline, where
  // two wisps swap depth order), then the visible pieces on top.
  draw_if([&](const vector::ViewEdge& e) { return outline(e, false); });
  pen.stroke(kHiddenColor, 1.0);
  draw_if([](const vector::ViewEdge& e) {
    return std::all_of(e.sources.begin(), e.sources.end(),
                       [](const vector::ViewEdgeSource& s) { return s.seam; });
  });
  pen.stroke(kSeamColor, 1.0);
  draw_if([&](const vector::ViewEdge& e) { return outline(e, true); });
  pen.stroke(kVisibleColor, 1.5);
}

void draw_curves(const Pen& pen, const InspectFrame& f) {
  const auto& wisps = f.result.wisps;
  cairo_t* cr = pen.cr;
  cairo_new_path(cr);
  // The handles: each span's end points to their inner control points.
  for (const vector::Wisp& w : wisps)
    for (int i = 0; i < w.centre.piece_count(); ++i) {
      const diffusion::Cubic c = w.centre.piece(i);
      pen.move(c[1]);
      pen.line(c[0]);
      pen.move(c[2]);
      pen.line(c[3]);
    }
  pen.stroke(kControlPolygonColor, 0.8);
  cairo_new_path(cr);
  for (const vector::Wisp& w : wisps) pen.bezier(w.centre);
  pen.stroke(kCurveColor, 1.0);
  cairo_new_path(cr);
  for (const vector::Wisp& w : wisps)
    for (int i = 0; i < w.centre.piece_count(); ++i) {
      const diffusion::Cubic c = w.centre.piece(i);
      pen.dot(c[1], 1.2);
      pen.dot(c[2], 1.2);
    }
  set_rgb(cr, kHandleColor);
  cairo_fill(cr);
  for (const vector::Wisp& w : wisps)
    for (int i = 0; i < w.centre.piece_count(); ++i) {
      if (i == 0) pen.square(w.centre.points.front(), 1.5);
      pen.square(w.centre.piece(i)[3], 1.5);
    }
  set_rgb(cr, kOnCurveColor);
  cairo_fill(cr);
}

void draw_vertices(const Pen& pen, const InspectFrame& f) {
  cairo_new_path(pen.cr);
  for (const vector::ViewVertex& v : f.result.arrangement.view.vertices)
    if (v.intersection) pen.dot(v.p, 2.0);
  set_rgb(pen.cr, kVertexColor);
  cairo_fill(pen.cr);
}

void draw_ink(const Pen& pen, const InspectFrame& f) {
  cairo_t* cr = pen.cr;
  const render::FramePicture& pic = f.result.picture;
  if (!pic.ink.empty()) {  // real strokes: as the PNG draws them, widths scaled with the view
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
    for (const render::InkStroke& s : pic.ink) {
      const Rgb8 color{to_byte(s.color[0]), to_byte(s.color[1]), to_byte(s.color[2])};
      for (const render::InkPiece& piece : render::ink_pieces(s)) {
        cairo_new_path(cr);
        pen.bezier(piece);
        pen.stroke(color, std::max(1.0, piece.width * pen.view.zoom));
      }
      if (s.curve.points.empty() && s.points.size() >= 2) {  // a polyline stroke: its mean width
        double width = 0;
        for (double w : s.width) width += w;
        width = s.width.empty() ? 1.0 : width / s.width.size();
        cairo_new_path(cr);
        pen.polyline(s.points, s.closed);
        pen.stroke(color, std::max(1.0, width * pen.view.zoom));
      }
    }
    return;
  }
  cairo_new_path(cr);
  for (const vector::InkLine& l : f.result.arrangement.occlusion) pen.polyline(l.points, l.closed);
  pen.stroke(kOcclusionColor, 1.5);
  cairo_new_path(cr);
  for (const vector::InkLine& l : f.result.arrangement.silhouette) pen.polyline(l.points, l.closed);
  pen.stroke(kSilhouetteColor, 2.0);
}

}  // namespace

const std::array<LayerInfo, kLayerCount>& layer_table() {
  return kLayers;
}

const LayerInfo& layer_info(Layer layer) {
  return kLayers[size_t(layer)];
}

std::vector<Layer> parse_layers(const std::string& list) {
  std::vector<Layer> out;
  std::stringstream in(list);
  std::string name;
  while (std::getline(in, name, ',')) {
    const auto it = std::find_if(kLayers.begin(), kLayers.end(),
                                 [&](const LayerInfo& l) { return name == l.name; });
    if (it == kLayers.end()) {
      std::string known;
      for (const LayerInfo& l : kLayers) known += std::string(known.empty() ? "" : ", ") + l.name;
      throw std::invalid_argument("--layers: unknown layer '" + name + "' (layers: " + known + ")");
    }
    out.push_back(it->layer);
  }
  if (out.empty()) throw std::invalid_argument("--layers: no layer named");
  return out;
}

int residual_step(const InspectFrame& frame, const LayerSet& layers) {
  const int steps = int(frame.residual.size());
  if (steps == 0) return -1;
  return layers.residual_step < 0 ? steps - 1 : std::min(layers.residual_step, steps - 1);
}

Rgb8 wisp_color(int wisp) {
  return hsv(0.618033988749895 * wisp, 0.75, 1.0);
}

Rgb8 face_color(int front, int number) {
  Rgb8 c = hsv(0.618033988749895 * front, 0.6, 0.85);
  for (int k = 0; k < 3; ++k)
    c[k] = std::uint8_t((c[k] & 0xe0) | ((number >> (kFaceCodeBits * k)) & 0x1f));
  return c;
}

namespace {

// 256 colours of an OpenCV colour map, RGB.
std::array<Rgb8, 256> colormap(int map) {
  cv::Mat ramp(1, 256, CV_8UC1), bgr;
  for (int i = 0; i < 256; ++i) ramp.at<std::uint8_t>(i) = std::uint8_t(i);
  cv::applyColorMap(ramp, bgr, map);
  std::array<Rgb8, 256> out;
  for (int i = 0; i < 256; ++i) {
    const cv::Vec3b c = bgr.at<cv::Vec3b>(i);
    out[i] = {c[2], c[1], c[0]};
  }
  return out;
}

}  // namespace

Rgb8 coverage_color(int count) {
  static const std::array<Rgb8, 256> plasma = colormap(cv::COLORMAP_PLASMA);
  const double t = double(std::clamp(count, 1, kCoverageLevels) - 1) / (kCoverageLevels - 1);
  return plasma[size_t(std::lround(40 + t * 215))];  // the darkest blues left out
}

Rgb8 residual_color(float residual) {
  static const std::array<Rgb8, 256> inferno = colormap(cv::COLORMAP_INFERNO);
  const double t =
      (std::log10(double(residual)) - kResidualLog10Min) / (kResidualLog10Max - kResidualLog10Min);
  // Never fully black: the darkest entries are left out so small residuals still show.
  return inferno[size_t(std::clamp(std::lround(40 + t * 215), 40L, 255L))];
}

cv::Mat draw_layers(const InspectFrame& frame, const LayerSet& layers, const ViewTransform& view,
                    cv::Size canvas) {
  Surface surface(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, canvas.width, canvas.height),
                  cairo_surface_destroy);
  if (cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS)
    throw std::runtime_error("cannot allocate a " + std::to_string(canvas.width) + "x" +
                             std::to_string(canvas.height) + " canvas");
  Context context(cairo_create(surface.get()), cairo_destroy);
  cairo_t* cr = context.get();
  set_rgb(cr, kBackground);
  cairo_paint(cr);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);

  const Pen pen{cr, view};
  const vector::ArrangementView& arr = frame.result.arrangement.view;
  bool first_area = true;
  for (const LayerInfo& info : kLayers) {
    if (!layers.has(info.layer)) continue;
    const double opacity = info.area && !first_area ? kStackedOpacity : 1.0;
    first_area = first_area && !info.area;
    cairo_save(cr);
    switch (info.layer) {
      case Layer::Image:
        draw_image(cr, frame, view, opacity);
        break;
      case Layer::Faces:
        paint_faces(cr, arr, view, opacity, [](const vector::ViewFace& f, int number) {
          return face_color(f.front, number);
        });
        break;
      case Layer::Coverage:
        paint_faces(cr, arr, view, opacity, [](const vector::ViewFace& f, int) {
          return coverage_color(int(f.cover.size()));
        });
        break;
      case Layer::Mask:
        draw_mask(cr, frame, view, opacity);
        break;
      case Layer::Constraints:
        draw_constraints(cr, frame, view, opacity, canvas);
        break;
      case Layer::Residual:
        draw_residual(cr, frame, layers, view, opacity);
        break;
      case Layer::Outlines:
        draw_outlines(pen, frame);
        break;
      case Layer::Visibility:
        draw_visibility(pen, frame);
        break;
      case Layer::Curves:
        draw_curves(pen, frame);
        break;
      case Layer::Vertices:
        draw_vertices(pen, frame);
        break;
      case Layer::Ink:
        draw_ink(pen, frame);
        break;
    }
    cairo_restore(cr);
  }
  cairo_surface_flush(surface.get());

  // Cairo's ARGB32 is B, G, R, A in memory on little-endian machines (all that wisp targets):
  // OpenCV's BGRA.
  const cv::Mat bgra(canvas.height, canvas.width, CV_8UC4,
                     cairo_image_surface_get_data(surface.get()),
                     size_t(cairo_image_surface_get_stride(surface.get())));
  cv::Mat bgr;
  cv::cvtColor(bgra, bgr, cv::COLOR_BGRA2BGR);
  return bgr;
}

}  // namespace wisp::inspect
