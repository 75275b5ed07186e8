// Frames as SVG: real paths for everything that is geometry (body, the hair base as a flat
// layer of its own, hair silhouette as a clip path, ink strokes, the wisp outlines in a hidden
// debug layer) and the smooth shading either embedded as a PNG clipped by the silhouette, or, in
// the flat style, one gradient-filled path per visible wisp region. Each layer is an Inkscape layer
// (kLayers below, one writer each) and every element's id says what it is (`wisp-17`,
// `ink-silhouette-3`), so an editor lists, hides and selects them by name. Written by hand: a plain
// text format whose structure (ids, layers) we control, which rsvg,
// Inkscape and browsers all read, and which apps/render/svg_animation.cpp reads back.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "apps/render/picture.hpp"
#include "io/atomic_file.hpp"
#include "io/image_file.hpp"
#include "io/png_encode.hpp"
#include "sim/body.hpp"

namespace wisp::render {
namespace {

std::string hex(const Rgb& c) {
  char buf[8];
  const auto b = [](float v) { return int(std::lround(std::clamp(v, 0.0f, 1.0f) * 255)); };
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", b(c[0]), b(c[1]), b(c[2]));
  return buf;
}

// Numbers with the picture's decimals (svg_decimals), without trailing zeros. Coordinates are
// rounded to whole units of 10^-decimals first, so relative path steps (differences of rounded
// points) add up exactly: no drift along a long path.
struct Num {
  Num(int d = 3) : decimals(d), scale(std::pow(10.0, d)) {}
  int decimals;
  double scale;
  long long units(double v) const { return std::llround(v * scale); }
  // Appends u units as a decimal number (digits written backwards into a buffer: no allocation).
  void append_units(std::string& out, long long u) const {
    char buf[32];
    char* end = buf + sizeof buf;
    char* p = end;
    unsigned long long m = u < 0 ? 0ULL - static_cast<unsigned long long>(u) : u;
    int fraction = decimals;
    while (fraction > 0 && m % 10 == 0) m /= 10, --fraction;  // trailing zeros go
    for (int i = 0; i < fraction; ++i) *--p = char('0' + m % 10), m /= 10;
    if (fraction > 0) *--p = '.';
    do *--p = char('0' + m % 10), m /= 10;
    while (m > 0);
    if (u < 0) *--p = '-';
    out.append(p, end);
  }
  std::string from_units(long long u) const {
    std::string s;
    append_units(s, u);
    return s;
  }
  std::string operator()(double v) const { return from_units(units(v)); }
};

// Path data in relative commands ("M x y l dx dy ... c ..."), about half the bytes of absolute
// ones for the same rounded points.
class PathData {
 public:
  explicit PathData(const Num& num) : num_(num) {}
  void move(const Eigen::Vector2d& p) {
    const auto [x, y] = units(p);
    if (!out_.empty()) out_ += ' ';
    out_ += 'M';
    num_.append_units(out_, x);
    out_ += ' ';
    num_.append_units(out_, y);
    cx_ = start_x_ = x, cy_ = start_y_ = y, last_ = 'M';
  }
  void line(const Eigen::Vector2d& p) {
    command('l');
    step(p);
    std::tie(cx_, cy_) = units(p);
  }
  void cubic(const Eigen::Vector2d& c1, const Eigen::Vector2d& c2, const Eigen::Vector2d& p) {
    command('c');
    step(c1), out_ += ' ', step(c2), out_ += ' ', step(p);
    std::tie(cx_, cy_) = units(p);
  }
  void close() {
    out_ += 'z';
    cx_ = start_x_, cy_ = start_y_, last_ = 'z';
  }
  const std::string& str() const { return out_; }

 private:
  std::pair<long long, long long> units(const Eigen::Vector2d& p) const {
    return {num_.units(p.x()), num_.units(p.y())};
  }
  // The command letter once for a run of the same command (the SVG grammar repeats it).
  void command(char c) {
    out_ += last_ == c ? ' ' : c;
    last_ = c;
  }
  void step(const Eigen::Vector2d& p) {
    const auto [x, y] = units(p);
    num_.append_units(out_, x - cx_);
    out_ += ' ';
    num_.append_units(out_, y - cy_);
  }
  const Num& num_;
  std::string out_;
  long long cx_ = 0, cy_ = 0, start_x_ = 0, start_y_ = 0;
  char last_ = 0;
};

// One layer's content is written by a function of the picture; definitions it references
// (gradients, clip paths) go to `defs`.
struct LayerText {
  std::ostringstream defs, body;
};
struct Writer {
  const FramePicture& pic;
  SvgStyle style;
  Num num;
};

void ring_path(PathData& d, const std::vector<Eigen::Vector2d>& ring) {
  if (ring.empty()) return;
  d.move(ring[0]);
  for (size_t i = 1; i < ring.size(); ++i) d.line(ring[i]);
  d.close();
}

// A Bezier path with at least one piece; `close` closes it (a filled region's loop).
void bezier_path(PathData& d, const diffusion::BezierPath& path, bool close = false) {
  d.move(path.points[0]);
  for (int i = 0; i < path.piece_count(); ++i) {
    const diffusion::Cubic c = path.piece(i);
    d.cubic(c[1], c[2], c[3]);
  }
  if (close) d.close();
}
std::string bezier_path(const Num& num, const diffusion::BezierPath& path) {
  PathData d(num);
  bezier_path(d, path);
  return d.str();
}

std::string mask_path(const Num& num, const vector::HairMask& mask) {
  PathData d(num);
  for (const vector::MaskPolygon& poly : mask.polygons) {
    ring_path(d, poly.outer);
    for (const auto& hole : poly.holes) ring_path(d, hole);
  }
  return d.str();
}

// `prefix` followed by the bytes in base64, written into a string of its final size (an image's
// data URI is a few hundred KB a frame).
std::string base64(const std::string& prefix, const std::vector<unsigned char>& bytes) {
  static const char* kTable = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const size_t n = bytes.size(), whole = n / 3 * 3;
  std::string out(prefix.size() + (n + 2) / 3 * 4, '=');
  char* o = std::copy(prefix.begin(), prefix.end(), out.data());
  const unsigned char* in = bytes.data();
  for (size_t i = 0; i < whole; i += 3, o += 4) {
    const unsigned v = unsigned(in[i]) << 16 | unsigned(in[i + 1]) << 8 | in[i + 2];
    o[0] = kTable[v >> 18], o[1] = kTable[(v >> 12) & 63];
    o[2] = kTable[(v >> 6) & 63], o[3] = kTable[v & 63];
  }
  if (whole < n) {  // one or two bytes left: the rest of the four characters stay '='
    const unsigned v =
        unsigned(in[whole]) << 16 | (whole + 1 < n ? unsigned(in[whole + 1]) << 8 : 0);
    o[0] = kTable[v >> 18], o[1] = kTable[(v >> 12) & 63];
    if (whole + 1 < n) o[2] = kTable[(v >> 6) & 63];
  }
  return out;
}

// The hair image's pixels in the frame's box [x0, x1) x [y0, y1) as a PNG data URI.
std::string png_data_uri(const FramePicture& pic, int x0, int y0, int x1, int y1) {
  const int w = x1 - x0, h = y1 - y0;
  // 0xffRRGGBB words, encoded as RGB; every one is written, so none is zeroed first.
  const std::unique_ptr<std::uint32_t[]> rgb(new std::uint32_t[size_t(w) * h]);
  pack_hair(pic, x0, y0, x1, y1, rgb.get(), size_t(w));
  const std::vector<std::uint8_t> png = io::encode_png(
      {reinterpret_cast<const std::uint8_t*>(rgb.get()), w, h, 3, size_t(w) * 4, true});
  return base64("data:image/png;base64,", png);
}

// The reblurred hair (premultiplied planes, FramePicture::blurred_hair) as an RGBA PNG: its alpha
// is the softened mask, so the image needs no clip path.
std::string rgba_data_uri(const std::vector<float>& planes, int width, int height) {
  const size_t n = size_t(width) * height;
  std::vector<std::uint8_t> rgba(4 * n);
  for (size_t i = 0; i < n; ++i) {
    const float a = planes[3 * n + i];
    for (int c = 0; c < 3; ++c)
      rgba[4 * i + c] = io::unit_byte(a > 0 ? planes[c * n + i] / a : 0.0f);
    rgba[4 * i + 3] = io::unit_byte(a);
  }
  const std::vector<std::uint8_t> png =
      io::encode_png({rgba.data(), width, height, 4, 4 * n / height});
  return base64("data:image/png;base64,", png);
}

// Vector layers under a blur map. SVG has no spatially varying blur, so each path (a flat wisp
// region, the hair base, an ink stroke) takes one Gaussian: the blur map's mean at its points,
// rounded to a half-octave level (0.5 px * 2^(k/2)); paths of one level share one group with
// one feGaussianBlur filter. Below kSharpest a path stays sharp (level -1).
constexpr double kSharpest = 0.35;

double mean_blur(const FramePicture& pic, const std::vector<Eigen::Vector2d>& points) {
  if (pic.blur.empty() || points.empty()) return 0;
  double sum = 0;
  for (const Eigen::Vector2d& p : points) {
    const int x = std::clamp(int(p.x()), 0, pic.width - 1);
    const int y = std::clamp(int(p.y()), 0, pic.height - 1);
    sum += pic.blur[size_t(y) * pic.width + x];
  }
  return sum / double(points.size());
}

int blur_level(double sigma) {
  return sigma < kSharpest ? -1 : std::max(0, int(std::lround(2 * std::log2(sigma / 0.5))));
}

double level_sigma(int level) {
  return 0.5 * std::pow(2.0, 0.5 * level);
}

std::vector<Eigen::Vector2d> area_points(const vector::HairMask& area) {
  std::vector<Eigen::Vector2d> out;
  for (const vector::MaskPolygon& p : area.polygons)
    out.insert(out.end(), p.outer.begin(), p.outer.end());
  return out;
}

// Writes the paths gathered per blur level, each level but the sharp one (-1) in a group with
// its filter.
void write_levels(std::ostringstream& o, std::map<int, std::ostringstream>& levels) {
  for (auto& [level, paths] : levels) {
    if (level >= 0) o << "<g filter=\"url(#blur" << level << ")\">\n";
    o << paths.str();
    if (level >= 0) o << "</g>\n";
  }
}

// The filters of the blur levels that a blurred picture's vector layers use (all of them up to
// the largest, a line each: unused ones cost nothing).
void blur_filters(std::ostringstream& o, const FramePicture& pic, const Num& num) {
  if (pic.blur.empty()) return;
  const float largest = *std::max_element(pic.blur.begin(), pic.blur.end());
  for (int level = 0; level <= blur_level(largest); ++level)
    o << "<filter id=\"blur" << level
      << "\" filterUnits=\"userSpaceOnUse\" x=\"0\" y=\"0\" width=\"" << pic.width << "\" height=\""
      << pic.height << "\"><feGaussianBlur stdDeviation=\"" << num(level_sigma(level))
      << "\"/></filter>\n";
}

// A variable-width stroke as one filled path: the left offsets forward, the right ones back.
std::string ink_outline(const Num& num, const InkStroke& ink) {
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
  PathData d(num);
  std::reverse(right.begin(), right.end());
  if (ink.closed) {
    ring_path(d, left);
    ring_path(d, right);
  } else {
    left.insert(left.end(), right.begin(), right.end());
    ring_path(d, left);
  }
  return d.str();
}

// Ink strokes, each with the id `prefix`-kind-n (n counting strokes of that kind from 1): one
// path, or a group of its constant-width pieces; under a blur map (`blur`), grouped by level.
void ink_strokes(std::ostringstream& o, const Num& num, const std::string& prefix,
                 const std::vector<InkStroke>& strokes, const FramePicture* blur = nullptr) {
  std::map<std::string, int> count;
  std::map<int, std::ostringstream> levels;
  for (const InkStroke& ink : strokes) {
    const std::string kind = ink.kind.empty() ? "stroke" : ink.kind;
    const std::string id = prefix + '-' + kind + '-' + std::to_string(++count[kind]);
    std::ostringstream& out = levels[blur ? blur_level(mean_blur(*blur, ink.points)) : -1];
    if (!ink.curve.points.empty()) {
      // Real strokes: constant-width pieces of the Bezier path (ink_pieces).
      const std::string color = hex(ink.color);
      const std::vector<InkPiece> pieces = ink_pieces(ink);
      if (pieces.empty()) continue;
      if (pieces.size() == 1) {
        out << "<path id=\"" << id << "\" d=\"" << bezier_path(num, pieces[0]) << "\" stroke=\""
            << color << "\" stroke-width=\"" << num(pieces[0].width) << "\"/>\n";
        continue;
      }
      out << "<g id=\"" << id << "\" stroke=\"" << color << "\">";
      for (const InkPiece& p : pieces)
        out << "<path d=\"" << bezier_path(num, p) << "\" stroke-width=\"" << num(p.width)
            << "\"/>";
      out << "</g>\n";
    } else if (ink.points.size() >= 2 && ink.width.size() == ink.points.size()) {
      out << "<path id=\"" << id << "\" d=\"" << ink_outline(num, ink) << "\" fill=\""
          << hex(ink.color) << "\" stroke=\"none\"/>\n";
    }
  }
  write_levels(o, levels);
}

const char* part_name(int part) {
  switch (part) {
    case sim::kBodyHead:
      return "head";
    case sim::kBodyNeck:
      return "neck";
    case sim::kBodyTorso:
      return "torso";
    case sim::kBodyArm:
      return "arm";
  }
  return "part";
}

void background_layer(const Writer& w, LayerText& out) {
  out.body << "<rect id=\"background-fill\" width=\"" << w.pic.width << "\" height=\""
           << w.pic.height << "\" fill=\"" << hex(w.pic.background) << "\"/>\n";
}

// One path per tone region (apps/render/body_paths.hpp), nonzero fill: no interior edges; then
// the face's lines, on the head and under the hair.
void body_layer(const Writer& w, LayerText& out) {
  std::map<std::string, int> count;
  for (const BodyPath& region : w.pic.body) {
    const std::string name = std::string(part_name(region.part)) + (region.shadow ? "-shadow" : "");
    PathData d(w.num);
    for (const auto& loop : region.loops)
      if (loop.size() >= 4) bezier_path(d, {loop}, true);
    out.body << "<path id=\"" << name << '-' << ++count[name] << "\" d=\"" << d.str()
             << "\" fill=\"" << hex(region.color) << "\"/>\n";
  }
  if (w.pic.face.empty()) return;
  out.body << "<g id=\"face\" fill=\"none\" stroke-linecap=\"round\" stroke-linejoin=\"round\">\n";
  ink_strokes(out.body, w.num, "face", w.pic.face);
  out.body << "</g>\n";
}

void hair_base_layer(const Writer& w, LayerText& out) {
  if (w.pic.base.polygons.empty()) return;
  std::map<int, std::ostringstream> levels;
  levels[blur_level(mean_blur(w.pic, area_points(w.pic.base)))]
      << "<path id=\"hair-base-fill\" fill-rule=\"evenodd\" d=\"" << mask_path(w.num, w.pic.base)
      << "\" fill=\"" << hex(w.pic.base_color) << "\"/>\n";
  write_levels(out.body, levels);
}

// The pixel box holding the mask (grown by a pixel for anti-aliasing), within the picture.
std::array<int, 4> mask_box(const vector::HairMask& mask, int width, int height) {
  double x0 = width, y0 = height, x1 = 0, y1 = 0;
  for (const vector::MaskPolygon& poly : mask.polygons)
    for (const Eigen::Vector2d& p : poly.outer) {
      x0 = std::min(x0, p.x()), y0 = std::min(y0, p.y());
      x1 = std::max(x1, p.x()), y1 = std::max(y1, p.y());
    }
  return {
      std::clamp(int(std::floor(x0)) - 1, 0, width), std::clamp(int(std::floor(y0)) - 1, 0, height),
      std::clamp(int(std::ceil(x1)) + 1, 0, width), std::clamp(int(std::ceil(y1)) + 1, 0, height)};
}

// The gradient stops that linear interpolation between their neighbours does not reproduce to
// within half a colour level (all that hex colours hold): a wisp of one colour but for its
// highlight needs a few stops, not all of them.
std::vector<std::pair<double, Rgb>> needed_stops(const std::vector<std::pair<double, Rgb>>& stops) {
  if (stops.size() <= 2) return stops;
  std::vector<std::pair<double, Rgb>> out = {stops.front()};
  const auto reproduced = [&](std::size_t from, std::size_t to) {
    const auto& [t0, c0] = stops[from];
    const auto& [t1, c1] = stops[to];
    for (std::size_t i = from + 1; i < to; ++i) {
      const double a = t1 > t0 ? (stops[i].first - t0) / (t1 - t0) : 0;
      const Rgb lerp = c0 + float(a) * (c1 - c0);
      if ((lerp - stops[i].second).cwiseAbs().maxCoeff() > 0.5f / 255) return false;
    }
    return true;
  };
  std::size_t kept = 0;
  for (std::size_t i = 1; i + 1 < stops.size(); ++i)
    if (!reproduced(kept, i + 1)) out.push_back(stops[i]), kept = i;
  out.push_back(stops.back());
  return out;
}

// Embedded: the shading where the hair is (the silhouette's pixel box) as an image clipped by
// the silhouette. Flat: each wisp's front region with its gradient, over an underlay: the hair
// (the silhouette but for the hair base's part) in the wisps' mean colour, so that where two
// regions meet, the pixels they share blend with hair colour rather than the layers below
// (a viewer anti-aliases each path on its own). The underlay stops a pixel short of the
// silhouette (masked by its own outline stroked 2 px wide): its partial pixels along the
// silhouette would add to the wisps' own there and grow the silhouette by about half a pixel, as
// a stroke around each region would.
void hair_layer(const Writer& w, LayerText& out) {
  const FramePicture& pic = w.pic;
  if (w.style == SvgStyle::Embedded && !pic.blurred_hair.empty()) {
    out.body << "<image id=\"hair-shading\" x=\"0\" y=\"0\" width=\"" << pic.width << "\" height=\""
             << pic.height << "\" preserveAspectRatio=\"none\" xlink:href=\""
             << rgba_data_uri(pic.blurred_hair, pic.width, pic.height) << "\"/>\n";
    return;
  }
  if (w.style == SvgStyle::Embedded) {
    const std::string silhouette = mask_path(w.num, pic.mask);
    if (pic.hair.planes.empty() || silhouette.empty()) return;
    const auto [x0, y0, x1, y1] = mask_box(pic.mask, pic.width, pic.height);
    if (x1 <= x0 || y1 <= y0) return;
    out.defs << "<clipPath id=\"hair-silhouette\" clipPathUnits=\"userSpaceOnUse\"><path "
                "clip-rule=\"evenodd\" d=\""
             << silhouette << "\"/></clipPath>\n";
    out.body << "<image id=\"hair-shading\" x=\"" << w.num(x0) << "\" y=\"" << w.num(y0)
             << "\" width=\"" << w.num(x1 - x0) << "\" height=\"" << w.num(y1 - y0)
             << "\" preserveAspectRatio=\"none\" clip-path=\"url(#hair-silhouette)\" "
             << "xlink:href=\"" << png_data_uri(pic, x0, y0, x1, y1) << "\"/>\n";
    return;
  }
  Rgb mean = Rgb::Zero();
  int n = 0;
  for (const FlatRegion& r : pic.flat)
    for (const auto& stop : r.stops) mean += stop.second, ++n;
  if (n > 0) {
    out.defs << "<path id=\"hair-shape\" fill-rule=\"evenodd\" d=\"" << mask_path(w.num, pic.mask)
             << ' ' << mask_path(w.num, pic.base) << "\"/>\n"
             << "<mask id=\"hair-inside\" maskUnits=\"userSpaceOnUse\" x=\"0\" y=\"0\" width=\""
             << pic.width << "\" height=\"" << pic.height
             << "\"><use xlink:href=\"#hair-shape\" fill=\"#fff\" stroke=\"#000\" "
                "stroke-width=\"2\"/></mask>\n";
    out.body << "<use id=\"hair-underlay\" xlink:href=\"#hair-shape\" fill=\""
             << hex(mean / float(n)) << "\" mask=\"url(#hair-inside)\"/>\n";
  }
  // Front regions do not overlap, so grouping them by blur level keeps the picture.
  std::map<int, std::ostringstream> levels;
  for (const FlatRegion& r : pic.flat) {
    const std::string id = "wisp-" + std::to_string(r.wisp);
    out.defs << "<linearGradient id=\"" << id
             << "-gradient\" gradientUnits=\"userSpaceOnUse\" x1=\"" << w.num(r.from.x())
             << "\" y1=\"" << w.num(r.from.y()) << "\" x2=\"" << w.num(r.to.x()) << "\" y2=\""
             << w.num(r.to.y()) << "\">";
    for (const auto& [offset, c] : needed_stops(r.stops))
      out.defs << "<stop offset=\"" << Num{4}(offset) << "\" stop-color=\"" << hex(c) << "\"/>";
    out.defs << "</linearGradient>\n";
    levels[blur_level(mean_blur(pic, area_points(r.area)))]
        << "<path id=\"" << id << "\" fill-rule=\"evenodd\" d=\"" << mask_path(w.num, r.area)
        << "\" fill=\"url(#" << id << "-gradient)\"/>\n";
  }
  write_levels(out.body, levels);
}

// Flat SVGs: each highlight filled with its colour, clipped to where its wisp is in front (a copy
// of its region's path: clip paths that only use the hair layer's paths would tie the layers
// together, and animation.svg could no longer share or rename them apart); in embedded SVGs the
// shading image holds them.
void highlights_layer(const Writer& w, LayerText& out) {
  std::map<int, const FlatRegion*> regions;
  for (const FlatRegion& r : w.pic.flat) regions[r.wisp] = &r;
  std::map<int, int> count;
  for (const Highlight& h : w.pic.highlights) {
    const auto region = regions.find(h.wisp);
    if (h.ring.size() < 3 || region == regions.end()) continue;
    const std::string front = "wisp-" + std::to_string(h.wisp) + "-front";
    if (count[h.wisp] == 0)
      out.defs << "<clipPath id=\"" << front << "\" clipPathUnits=\"userSpaceOnUse\"><path "
               << "clip-rule=\"evenodd\" d=\"" << mask_path(w.num, region->second->area)
               << "\"/></clipPath>\n";
    PathData d(w.num);
    ring_path(d, h.ring);
    out.body << "<path id=\"highlight-" << h.wisp << '-' << ++count[h.wisp] << "\" d=\"" << d.str()
             << "\" fill=\"" << hex(h.color) << "\" clip-path=\"url(#" << front << ")\"/>\n";
  }
}

void hatching_layer(const Writer& w, LayerText& out) {
  ink_strokes(out.body, w.num, "hatching", w.pic.hatching);
}

// Fur tufts back to front, each one nonzero-filled path (its strands' loops) at its opacity.
void fur_layer(const Writer& w, LayerText& out) {
  int n = 0;
  for (const vector::FurTuft& tuft : w.pic.fur) {
    PathData d(w.num);
    for (const auto& loop : tuft.loops)
      if (loop.size() >= 4) bezier_path(d, {loop}, true);
    out.body << "<path id=\"tuft-" << ++n << "\" d=\"" << d.str() << "\" fill=\"" << hex(tuft.color)
             << "\" fill-opacity=\"" << w.num(tuft.opacity) << "\"/>\n";
  }
}

void ink_layer(const Writer& w, LayerText& out) {
  blur_filters(out.defs, w.pic, w.num);
  ink_strokes(out.body, w.num, "ink", w.pic.ink, w.pic.blur.empty() ? nullptr : &w.pic);
}

void outlines_layer(const Writer& w, LayerText& out) {
  for (const WispOutline& outline : w.pic.outlines)
    if (outline.path.piece_count() > 0)
      out.body << "<path id=\"outline-" << outline.wisp << "\" d=\""
               << bezier_path(w.num, outline.path) << "\"/>\n";
}

// The layers, back to front: id, label, whether hidden, attributes its content inherits, writer.
struct LayerEntry {
  SvgLayer layer;
  const char* attributes;
  void (*write)(const Writer&, LayerText&);
};
const LayerEntry kLayers[] = {
    {{"background", "background"}, "", background_layer},
    {{"body", "body"}, " stroke=\"none\"", body_layer},
    {{"hair-base", "hair base"}, "", hair_base_layer},
    {{"hair", "hair"}, "", hair_layer},
    {{"highlights", "highlights"}, "", highlights_layer},
    {{"hatching", "hatching"},
     " fill=\"none\" stroke-linecap=\"round\" stroke-linejoin=\"round\"",
     hatching_layer},
    {{"fur", "fur"}, " fill-rule=\"nonzero\" stroke=\"none\"", fur_layer},
    {{"ink", "ink"},
     " fill=\"none\" stroke-linecap=\"round\" stroke-linejoin=\"round\"",
     ink_layer},
    {{"wisp-outlines", "wisp outlines (debug)", true},
     " fill=\"none\" stroke=\"#ff00ff\" stroke-width=\"0.5\"",
     outlines_layer},
};

}  // namespace

std::vector<SvgLayer> svg_layers() {
  std::vector<SvgLayer> out;
  for (const LayerEntry& e : kLayers) out.push_back(e.layer);
  return out;
}

int svg_decimals(int width, int height) {
  const double tolerance = std::max({width, height, 1}) / 65536.0;
  int d = 0;
  while (d < 6 && 0.5 * std::pow(10.0, -d) > tolerance) ++d;
  return d;
}

std::string format_frame_svg(const FramePicture& pic, SvgStyle style) {
  const Writer w{pic, style, {svg_decimals(pic.width, pic.height)}};
  std::ostringstream defs, layers;
  for (const LayerEntry& e : kLayers) {
    LayerText t;
    e.write(w, t);
    defs << t.defs.str();
    layers << "<g id=\"" << e.layer.id << "\" inkscape:groupmode=\"layer\" inkscape:label=\""
           << e.layer.label << '"' << (e.layer.hidden ? " style=\"display:none\"" : "")
           << e.attributes << ">\n"
           << t.body.str() << "</g>\n";
  }
  std::ostringstream o;
  o << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    << "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:xlink=\"http://www.w3.org/1999/xlink\" "
    << "xmlns:inkscape=\"http://www.inkscape.org/namespaces/inkscape\" "
    << "xmlns:sodipodi=\"http://sodipodi.sourceforge.net/DTD/sodipodi-0.dtd\" width=\"" << pic.width
    << "\" height=\"" << pic.height << "\" viewBox=\"0 0 " << pic.width << ' ' << pic.height
    << "\">\n<defs>\n"
    << defs.str() << "</defs>\n"
    << layers.str() << "</svg>\n";
  return o.str();
}

void write_frame_svg(const FramePicture& pic, const std::filesystem::path& path, SvgStyle style) {
  const std::string text = format_frame_svg(pic, style);
  io::write_text_atomically(path, text);
}

}  // namespace wisp::render
