// Frames as SVG: real paths for everything that is geometry (body, the hair base as a flat
// layer of its own, hair silhouette as a clip path, ink strokes, the wisp outlines in a hidden
// debug group) and the smooth shading either embedded as a PNG clipped by the silhouette, or, in
// the flat style, one gradient-filled path per visible wisp region. Written by hand: a plain text
// format whose structure (ids, groups, hidden layers) we control, which rsvg, Inkscape and browsers
// all read.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "apps/render/picture.hpp"
#include "io/atomic_file.hpp"
#include "io/png_encode.hpp"

namespace wisp::render {
namespace {

std::string hex(const Rgb& c) {
  char buf[8];
  const auto b = [](float v) { return int(std::lround(std::clamp(v, 0.0f, 1.0f) * 255)); };
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", b(c[0]), b(c[1]), b(c[2]));
  return buf;
}

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", v);
  std::string s = buf;
  while (!s.empty() && s.back() == '0') s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  return s == "-0" ? "0" : s;
}

void ring_path(std::ostringstream& o, const std::vector<Eigen::Vector2d>& ring) {
  for (size_t i = 0; i < ring.size(); ++i)
    o << (i ? " L" : "M") << num(ring[i].x()) << ' ' << num(ring[i].y());
  if (!ring.empty()) o << " Z";
}

// Path data "M x y C ... C ... [Z]" of a Bezier path with at least one piece; `close` closes it
// (a filled region's loop).
std::string bezier_path(const diffusion::BezierPath& path, bool close = false) {
  std::ostringstream o;
  o << 'M' << num(path.points[0].x()) << ' ' << num(path.points[0].y());
  for (int i = 0; i < path.piece_count(); ++i) {
    const diffusion::Cubic c = path.piece(i);
    o << " C" << num(c[1].x()) << ' ' << num(c[1].y()) << ' ' << num(c[2].x()) << ' '
      << num(c[2].y()) << ' ' << num(c[3].x()) << ' ' << num(c[3].y());
  }
  if (close) o << " Z";
  return o.str();
}

std::string mask_path(const vector::MaskPolygon& poly) {
  std::ostringstream o;
  ring_path(o, poly.outer);
  for (const auto& hole : poly.holes) {
    o << ' ';
    ring_path(o, hole);
  }
  return o.str();
}

std::string mask_path(const vector::HairMask& mask) {
  std::string out;
  for (const vector::MaskPolygon& poly : mask.polygons) out += mask_path(poly) + ' ';
  return out;
}

std::string base64(const std::vector<unsigned char>& bytes) {
  static const char* kTable = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const unsigned v = unsigned(bytes[i]) << 16 | (i + 1 < bytes.size() ? bytes[i + 1] << 8 : 0) |
                       (i + 2 < bytes.size() ? bytes[i + 2] : 0);
    out += kTable[(v >> 18) & 63];
    out += kTable[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? kTable[(v >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kTable[v & 63] : '=';
  }
  return out;
}

std::string png_data_uri(const diffusion::Image& img) {
  const size_t n = size_t(img.width) * img.height;
  std::vector<std::uint8_t> rgb(3 * n);
  for (size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c)
      rgb[3 * i + c] = static_cast<std::uint8_t>(
          std::lround(std::clamp(img.planes[c * n + i], 0.0f, 1.0f) * 255));
  const std::vector<std::uint8_t> png =
      io::encode_png({rgb.data(), img.width, img.height, 3, size_t(img.width) * 3});
  return "data:image/png;base64," + base64(png);
}

// A variable-width stroke as one filled path: the left offsets forward, the right ones back.
std::string ink_outline(const InkStroke& ink) {
  const size_t n = ink.points.size();
  std::vector<Eigen::Vector2d> left, right;
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d prev = ink.points[i > 0 ? i - 1 : (ink.closed ? n - 1 : 0)];
    const Eigen::Vector2d next = ink.points[i + 1 < n ? i + 1 : (ink.closed ? 0 : n - 1)];
    Eigen::Vector2d d = next - prev;
    if (d.norm() < 1e-9) d = Eigen::Vector2d(1, 0);
    const Eigen::Vector2d nrm = Eigen::Vector2d(-d.y(), d.x()).normalized() * (0.5 * ink.width[i]);
    left.push_back(ink.points[i] + nrm);
    right.push_back(ink.points[i] - nrm);
  }
  std::ostringstream o;
  if (ink.closed) {
    ring_path(o, left);
    o << ' ';
    std::reverse(right.begin(), right.end());
    ring_path(o, right);
  } else {
    std::reverse(right.begin(), right.end());
    left.insert(left.end(), right.begin(), right.end());
    ring_path(o, left);
  }
  return o.str();
}

// A group of ink strokes.
void ink_group(std::ostringstream& o, const char* id, const std::vector<InkStroke>& strokes) {
  o << " <g id=\"" << id
    << "\" fill=\"none\" stroke-linecap=\"round\" stroke-linejoin=\"round\">\n";
  for (const InkStroke& ink : strokes) {
    if (!ink.curve.points.empty()) {
      // Real strokes: constant-width pieces of the Bezier path (ink_pieces, as in the PNG).
      const std::string color = hex(ink.color);
      for (const InkPiece& piece : ink_pieces(ink)) {
        o << "  <path d=\"" << bezier_path(piece) << "\" stroke=\"" << color << "\" stroke-width=\""
          << num(piece.width) << "\"/>\n";
      }
    } else if (ink.points.size() >= 2 && ink.width.size() == ink.points.size()) {
      o << "  <path d=\"" << ink_outline(ink) << "\" fill=\"" << hex(ink.color)
        << "\" stroke=\"none\"/>\n";
    }
  }
  o << " </g>\n";
}

}  // namespace

std::string format_frame_svg(const FramePicture& pic, SvgStyle style) {
  std::ostringstream o;
  o << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    << "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:xlink=\"http://www.w3.org/1999/xlink\" "
    << "width=\"" << pic.width << "\" height=\"" << pic.height << "\" viewBox=\"0 0 " << pic.width
    << ' ' << pic.height << "\">\n";
  o << " <rect id=\"background\" width=\"" << pic.width << "\" height=\"" << pic.height
    << "\" fill=\"" << hex(pic.background) << "\"/>\n";
  // One path per tone region (apps/render/body_paths.hpp), nonzero fill: no interior edges.
  o << " <g id=\"body\" fill-rule=\"nonzero\" stroke=\"none\">\n";
  for (const BodyPath& region : pic.body) {
    o << "  <path d=\"";
    for (const auto& loop : region.loops)
      if (loop.size() >= 4) o << bezier_path({loop}, true) << ' ';
    o << "\" fill=\"" << hex(region.color) << "\"/>\n";
  }
  o << " </g>\n";
  ink_group(o, "face", pic.face);  // on the head, under the hair

  if (!pic.base.polygons.empty())
    o << " <g id=\"hair-base\" fill-rule=\"evenodd\">\n  <path d=\"" << mask_path(pic.base)
      << "\" fill=\"" << hex(pic.base_color) << "\"/>\n </g>\n";

  const std::string silhouette = mask_path(pic.mask);
  if (style == SvgStyle::Embedded) {
    o << " <defs>\n  <clipPath id=\"hair-silhouette\" clipPathUnits=\"userSpaceOnUse\">\n"
      << "   <path clip-rule=\"evenodd\" d=\"" << silhouette << "\"/>\n  </clipPath>\n </defs>\n";
    if (!pic.hair.planes.empty() && !silhouette.empty())
      o << " <image id=\"hair\" x=\"0\" y=\"0\" width=\"" << pic.width << "\" height=\""
        << pic.height << "\" preserveAspectRatio=\"none\" clip-path=\"url(#hair-silhouette)\" "
        << "xlink:href=\"" << png_data_uri(pic.hair) << "\"/>\n";
  } else {
    o << " <defs>\n";
    for (size_t i = 0; i < pic.flat.size(); ++i) {
      const FlatRegion& r = pic.flat[i];
      o << "  <linearGradient id=\"wisp" << i << "\" gradientUnits=\"userSpaceOnUse\" x1=\""
        << num(r.from.x()) << "\" y1=\"" << num(r.from.y()) << "\" x2=\"" << num(r.to.x())
        << "\" y2=\"" << num(r.to.y()) << "\">";
      for (const auto& [offset, c] : r.stops)
        o << "<stop offset=\"" << num(offset) << "\" stop-color=\"" << hex(c) << "\"/>";
      o << "</linearGradient>\n";
    }
    o << " </defs>\n <g id=\"hair\" fill-rule=\"evenodd\">\n";
    for (size_t i = 0; i < pic.flat.size(); ++i)
      o << "  <path d=\"" << mask_path(pic.flat[i].area) << "\" fill=\"url(#wisp" << i
        << ")\" stroke=\"url(#wisp" << i << ")\" stroke-width=\"0.5\"/>\n";
    o << " </g>\n";
  }

  o << " <g id=\"wisp-outlines\" style=\"display:none\" fill=\"none\" stroke=\"#ff00ff\" "
       "stroke-width=\"0.5\">\n";
  for (const diffusion::BezierPath& outline : pic.outlines)
    if (outline.piece_count() > 0) o << "  <path d=\"" << bezier_path(outline) << "\"/>\n";
  o << " </g>\n";
  if (!pic.fur.empty()) {
    o << " <g id=\"fur\" fill-rule=\"nonzero\" stroke=\"none\">\n";
    for (const vector::FurTuft& tuft : pic.fur) {
      o << "  <path d=\"";
      for (const auto& loop : tuft.loops)
        if (loop.size() >= 4) o << bezier_path({loop}, true) << ' ';
      o << "\" fill=\"" << hex(tuft.color) << "\" fill-opacity=\"" << num(tuft.opacity) << "\"/>\n";
    }
    o << " </g>\n";
  }
  ink_group(o, "ink", pic.ink);
  o << "</svg>\n";
  return o.str();
}

void write_frame_svg(const FramePicture& pic, const std::filesystem::path& path, SvgStyle style) {
  const std::string text = format_frame_svg(pic, style);
  io::write_text_atomically(path, text);
}

}  // namespace wisp::render
