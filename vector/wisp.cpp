// Wisp construction: sample selection, centre spline, clamped extrusion, cubic outline fit and the
// flattened band (sections) used by the arrangement.
#include "vector/wisp.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "vector/catmull_rom.hpp"

namespace wisp::vector {

using diffusion::Cubic;
using diffusion::derivative;
using diffusion::eval;
using diffusion::flatten_pieces;
using diffusion::line_cubic;
using diffusion::reversed;
using diffusion::second_derivative;
using Eigen::Vector2d;
using Eigen::Vector3d;

namespace {

double cross(const Vector2d& a, const Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

[[noreturn]] void fail(const sim::ProjectedStrand& s, const std::string& what) {
  throw std::invalid_argument("strand " + std::to_string(s.id) + ": " + what);
}

void check_strand(const sim::ProjectedStrand& s) {
  const size_t n = s.pixel.size();
  auto check_size = [&](size_t size, const char* name, bool may_be_empty) {
    if (size != n && !(may_be_empty && size == 0))
      fail(s, std::string(name) + " has " + std::to_string(size) + " entries, pixel has " +
                  std::to_string(n));
  };
  check_size(s.depth.size(), "depth", false);
  check_size(s.tangent.size(), "tangent", true);
  check_size(s.visible.size(), "visible", true);
  check_size(s.width.size(), "width", true);
  for (size_t i = 0; i < n; ++i) {
    // The message's prefix is made only for a failure (most samples pass).
    auto at = [i] { return "sample " + std::to_string(i) + ": "; };
    if (!s.pixel[i].allFinite()) fail(s, at() + "pixel is not finite");
    if (!std::isfinite(s.depth[i]) || s.depth[i] <= 0)
      fail(s, at() + "depth must be finite and > 0, got " + std::to_string(s.depth[i]));
    if (!s.tangent.empty() && !s.tangent[i].allFinite()) fail(s, at() + "tangent is not finite");
    if (!s.width.empty() && !(std::isfinite(s.width[i]) && s.width[i] >= 0))
      fail(s, at() + "width must be finite and >= 0, got " + std::to_string(s.width[i]));
  }
}

// The longest run [first, last] of usable samples, the one nearest the root on ties.
std::pair<int, int> usable_run(const sim::ProjectedStrand& s, const WispStyle& style) {
  auto usable = [&](size_t i) {
    if (s.pixel[i].cwiseAbs().maxCoeff() > style.max_coordinate_px) return false;
    return !style.trim_hidden || s.visible.empty() || s.visible[i] != 0;
  };
  std::pair<int, int> best{0, -1};
  for (int i = 0, n = int(s.pixel.size()); i < n;) {
    if (!usable(i)) {
      ++i;
      continue;
    }
    int j = i;
    while (j + 1 < n && usable(j + 1)) ++j;
    if (j - i > best.second - best.first) best = {i, j};
    i = j + 1;
  }
  return best;
}

// One centre span with the depth and strand parameter at its ends (both linear in v), and the
// strand's own full width there when it stands for a clump (w0 < 0: the style's width).
struct Span {
  Cubic b;
  double z0, z1, u0, u1;
  double w0 = -1, w1 = -1;
};

constexpr int kWidthSamples = 16;  // per span, for the width limit table

// A point of the centre line: a kept sample, or a square cap's end.
struct CentrePoint {
  Vector2d pixel;
  double depth, u;  // u: the strand parameter
  Vector3d tangent;
  double width;  // the clump's full width (scene units), -1 for the style's
};

// A clump's strands reach past its guide's ends by about the clump's spread (their roots lie
// around the guide's on the scalp, some are longer): a wisp that stands for a clump goes on
// straight past each end by its half-width there, like a stroke's square cap, with the end's
// depth, strand parameter, tangent and width.
void square_caps(std::vector<CentrePoint>& points, double focal_px, const WispStyle& style) {
  const auto cap = [&](const CentrePoint& end, const CentrePoint& inner) {
    CentrePoint p = end;
    const Vector2d d = (end.pixel - inner.pixel).normalized();
    const double half = std::min(0.5 * end.width * focal_px / end.depth, style.max_width_px);
    p.pixel = end.pixel + half * d;
    return p;
  };
  const CentrePoint root = cap(points[0], points[1]), tip = cap(points.back(), points.end()[-2]);
  if ((root.pixel - points[0].pixel).norm() > style.merge_distance_px)
    points.insert(points.begin(), root);
  if ((tip.pixel - points.back().pixel).norm() > style.merge_distance_px) points.push_back(tip);
}

// The offset curves p(v) = B(v) + N(v) d_left(v) and B(v) - N(v) d_right(v) of each span.
//
// Width limit: an offset at distance d from a curve folds over itself (a swallowtail) once it
// passes a centre of curvature of the curve nearby, not only its own (Faraj's loops on curly
// hair). So each side's half-width at a point is capped by curvature_clamp times the distance
// from the point to every centre of curvature that lies on that side within an arc length of
// twice the unclamped width. At the point itself that is the radius of curvature; near a tight
// crest it makes the inner side narrow gradually (the cap is 1-Lipschitz along the curve), while
// the outer side keeps its full width. A second cap handles folds that no curvature sees in time
// (a sharp V, neighbouring arches of a coil): half the gap to a part of the curve that faces this
// side and is much nearer in space than along the curve. Self-crossings of the centre curve
// itself (loops of a coil seen edge-on) are left to overlap: the arrangement counts windings.
//
// The arrays live in an ExtruderArrays that the wisps of a frame share, so that a wisp does not
// allocate them again.
struct ExtruderArrays {
  std::vector<std::array<double, 2>> width;
  std::vector<double> scale;
  // limit_widths' per-sample table and bounds.
  std::vector<Vector2d> b, normal, centre;
  std::vector<char> has_centre;
  std::vector<double> arc, free, radius, turning;
  std::vector<Eigen::AlignedBox2d> box;
  std::vector<int> tight;
};

struct Extruder {
  const std::vector<Span>& spans;
  const WispStyle& style;
  double focal_px;
  std::vector<std::array<double, 2>>& width;  // [span * kWidthSamples + j] = {left, right}
  std::vector<double>& scale;                 // per span: its control polygon's length

  Extruder(const std::vector<Span>& s, const WispStyle& st, double f, ExtruderArrays& arrays)
      : spans(s), style(st), focal_px(f), width(arrays.width), scale(arrays.scale) {
    scale.clear();
    for (const Span& span : s) {
      const Cubic& c = span.b;
      scale.push_back((c[3] - c[0]).norm() + (c[1] - c[0]).norm() + (c[2] - c[1]).norm());
    }
    limit_widths(arrays);
  }

  double depth(int i, double v) const { return spans[i].z0 + (spans[i].z1 - spans[i].z0) * v; }

  // Unit direction of travel; at a cusp (a hairpin in the samples) B' vanishes and the limit
  // direction is that of B''.
  // `d1`: B'(v).
  Vector2d direction(int i, double v, Vector2d d1) const {
    const Cubic& c = spans[i].b;
    if (d1.norm() <= 1e-12 * scale[i]) d1 = second_derivative(c, v) * (v < 0.5 ? 1 : -1);
    if (d1.norm() <= 1e-12 * scale[i]) d1 = c[3] - c[0];
    const double n = d1.norm();
    return n > 0 ? Vector2d(d1 / n) : Vector2d(1, 0);
  }

  Vector2d left_normal(int i, double v, const Vector2d& d1) const {
    const Vector2d d = direction(i, v, d1);
    return {d.y(), -d.x()};
  }
  Vector2d left_normal(int i, double v) const {
    return left_normal(i, v, derivative(spans[i].b, v));
  }

  // Perspective width times the profile and the root taper, before any limit. A clump's width
  // is its own profile: neither the style's profile nor the root taper applies.
  double free_width(int i, double v) const {
    const Span& s = spans[i];
    if (s.w0 >= 0)
      return std::min(0.5 * (s.w0 + (s.w1 - s.w0) * v) * focal_px / depth(i, v),
                      style.max_width_px);
    const double u = s.u0 + (s.u1 - s.u0) * v;
    const double taper =
        u < style.root_taper ? std::sin(0.5 * M_PI * std::max(0.0, u) / style.root_taper) : 1.0;
    const double h = 0.5 * style.width * focal_px / depth(i, v) * style.profile.at(u) * taper;
    return std::min(h, style.max_width_px);
  }

  void limit_widths(ExtruderArrays& arrays) {
    const int n = int(spans.size()) * kWidthSamples + 1;
    std::vector<Vector2d>&b = arrays.b, &normal = arrays.normal, &centre = arrays.centre;
    std::vector<char>& has_centre = arrays.has_centre;
    std::vector<double>&arc = arrays.arc, &free = arrays.free;
    b.resize(n), normal.resize(n), centre.resize(n), free.resize(n);
    has_centre.assign(n, 0);
    arc.assign(n, 0);
    for (int g = 0; g < n; ++g) {
      const int i = std::min(g / kWidthSamples, int(spans.size()) - 1);
      const double v = double(g - i * kWidthSamples) / kWidthSamples;
      const Cubic& c = spans[i].b;
      const Vector2d d1 = derivative(c, v), d2 = second_derivative(c, v);
      b[g] = eval(c, v);
      normal[g] = left_normal(i, v, d1);
      free[g] = free_width(i, v);
      if (g > 0) arc[g] = arc[g - 1] + (b[g] - b[g - 1]).norm();
      const double k = cross(d1, d2), speed2 = d1.squaredNorm();
      // Centre of curvature B + |B'|^2 / (B' x B'') * perp(B'); a cusp is its own centre.
      if (speed2 == 0) {
        centre[g] = b[g], has_centre[g] = 1;
      } else if (std::abs(k) > 1e-12 * speed2 * std::sqrt(speed2)) {
        centre[g] = b[g] + speed2 / k * Vector2d(-d1.y(), d1.x());
        has_centre[g] = 1;
      }
    }
    // Bounds by which the scans below pass over samples that cannot lower a width (a width is the
    // least of its caps, so leaving out one that is not below it changes nothing): the radius of
    // curvature per sample, the box of the samples per block (a span's), and the turning of the
    // sample polyline summed from its start. The directions along a stretch that turns by at most
    // 60 degrees in all lie within 30 degrees of a middle one, so the stretch is at least
    // cos 30 > 1 / 1.2 of its arc length long from end to end: it holds no fold.
    const int blocks = (n + kWidthSamples - 1) / kWidthSamples;
    std::vector<double>& radius = arrays.radius;
    std::vector<Eigen::AlignedBox2d>& box = arrays.box;
    radius.assign(n, INFINITY);
    box.assign(blocks, Eigen::AlignedBox2d());
    double extent = arc[n - 1];
    for (int g = 0; g < n; ++g) {
      const int k = g / kWidthSamples;
      if (has_centre[g]) radius[g] = (centre[g] - b[g]).norm();
      box[k].extend(b[g]);
      extent = std::max(extent, b[g].cwiseAbs().maxCoeff());
    }
    const double slack = 1e-9 * (extent + 1);  // far above the rounding of arc lengths and gaps
    auto past_block = [&](int k, int dir) {    // the last sample of block k in direction dir
      return dir > 0 ? std::min(n, (k + 1) * kWidthSamples) - 1 : k * kWidthSamples;
    };
    // turning[k]: at least the turning from segment 0 (b[0] -> b[1]) to segment k. Unit
    // directions a chord c <= 1 apart differ by 2 asin(c / 2) <= (pi / 3) c; above, count a half
    // turn. A segment of length zero keeps the direction before it.
    constexpr double kStraight = M_PI / 3;
    std::vector<double>& turning = arrays.turning;
    turning.assign(n, 0);
    Vector2d heading(0, 0);
    for (int k = 0; k + 1 < n; ++k) {
      const double length = arc[k + 1] - arc[k];
      double turn = 0;
      if (length > 0) {
        const Vector2d d = (b[k + 1] - b[k]) / length;
        if (heading != Vector2d(0, 0)) {
          const double c = (d - heading).norm();
          turn = c <= 1 ? 1.0472 * c : M_PI;
        }
        heading = d;
      }
      turning[k] = (k > 0 ? turning[k - 1] : 0) + turn;
    }
    // The centres that can lower some width: a radius below (2 + 1 / clamp) free widths.
    const double free_max = *std::max_element(free.begin(), free.end());
    std::vector<int>& tight = arrays.tight;
    tight.clear();
    for (int j = 0; j < n; ++j)
      if (has_centre[j] &&
          !(style.curvature_clamp * (radius[j] - 2 * free_max - slack) >= free_max))
        tight.push_back(j);
    int next_tight = 0;  // per g, the first tight centre after g
    // Per g, the segments from g on (before g) within kStraight of turning end at ahead (behind).
    int ahead = 0, behind = 0;

    // The scans read plain arrays and keep the widths in two locals: with the table's vectors
    // and the style behind references, each store to a width made the compiler load them again.
    const double clamp = style.curvature_clamp;
    const Vector2d *b_at = b.data(), *normal_at = normal.data(), *centre_at = centre.data();
    const double *arc_at = arc.data(), *free_at = free.data(), *radius_at = radius.data();
    const double* turning_at = turning.data();
    const int* tight_at = tight.data();
    const int tight_count = int(tight.size());
    width.resize(n);
    for (int g = 0; g < n; ++g) {
      double left = free_at[g], right = free_at[g];
      const Vector2d bg = b_at[g], ng = normal_at[g];
      const double ag = arc_at[g], fg = free_at[g];
      auto lower = [&](bool on_left, double cap) {  // on_left: towards +N
        if (on_left) {
          if (cap < left) left = cap;
        } else if (cap < right) {
          right = cap;
        }
      };
      // Centres of curvature on each side, within twice the free width along the curve: only
      // the tight ones can lower a width. A centre of radius R at arc distance a lies at least
      // R - a away.
      while (next_tight < tight_count && tight_at[next_tight] <= g) ++next_tight;
      for (int dir : {-1, +1}) {
        for (int t = dir < 0 ? next_tight - 1 : next_tight; t >= 0 && t < tight_count; t += dir) {
          const int j = tight_at[t];
          if (!(std::abs(arc_at[j] - ag) <= 2 * fg)) break;
          if (clamp * (radius_at[j] - std::abs(arc_at[j] - ag) - slack) >= std::max(left, right))
            continue;
          const Vector2d to = centre_at[j] - bg;
          lower(to.dot(ng) > 0, clamp * to.norm());
        }
      }
      // Folds: where the curve bends back (a sharp V, the next arch of a coil), a point of it
      // ahead of this side (within 60 degrees of the normal) that is much nearer in space than
      // along the curve; each of the two passes may take half the gap.
      for (ahead = std::max(ahead, g);
           ahead < n - 1 && turning_at[ahead] <= turning_at[g] + kStraight;)
        ++ahead;
      while (g > 0 && behind < g - 1 && turning_at[behind] < turning_at[g - 1] - kStraight)
        ++behind;
      for (int dir : {-1, +1}) {
        // The first sample past the straight stretch from g.
        const int straight_end = dir > 0 ? (ahead < n - 1 ? ahead + 1 : n)
                                 : g > 0 ? behind - 1
                                         : -1;
        int block = -1;
        for (int j = g + dir; j >= 0 && j < n && std::abs(arc_at[j] - ag) <= 8 * fg; j += dir) {
          if ((j - straight_end) * dir < 0 && std::abs(arc_at[j] - ag) > slack) {
            j = straight_end - dir;
            continue;
          }
          if (const int k = j / kWidthSamples; k != block) {
            block = k;
            // Half the gap to any sample of the block cannot lower either side.
            const double far = std::max(left, right) * (2 / clamp) + slack;
            if (box[k].squaredExteriorDistance(bg) >= far * far) {
              j = past_block(k, dir);
              continue;
            }
          }
          const Vector2d to = b_at[j] - bg;
          const double gap = to.norm(), along = to.dot(ng);
          if (std::abs(arc_at[j] - ag) < 1.2 * gap || std::abs(along) < 0.5 * gap) continue;
          lower(along > 0, 0.5 * clamp * gap);
        }
      }
      width[g] = {left < 1e-9 ? 0.0 : left, right < 1e-9 ? 0.0 : right};
    }
  }

  // Half-widths of the left and the right side: monotone cubic (Fritsch-Carlson) interpolation of
  // the table, C1 so the Hermite outline fits need few pieces, and never above its neighbours.
  std::array<double, 2> half_widths(int i, double v) const {
    const double x = std::clamp(v, 0.0, 1.0) * kWidthSamples;
    const int j = std::min(int(x), kWidthSamples - 1);
    const double f = x - j;
    const int g = i * kWidthSamples + j, n = int(width.size());
    const double f2 = f * f, f3 = f2 * f;
    std::array<double, 2> out;
    for (int side = 0; side < 2; ++side) {
      auto w = [&](int k) { return width[std::clamp(k, 0, n - 1)][side]; };
      auto slope = [&](int k) {
        const double a = w(k) - w(k - 1), b = w(k + 1) - w(k);
        return a * b <= 0 ? 0.0 : 2 * a * b / (a + b);  // harmonic mean, zero at extrema
      };
      const double y0 = w(g), y1 = w(g + 1), m0 = slope(g), m1 = slope(g + 1);
      out[side] = std::max(0.0, (2 * f3 - 3 * f2 + 1) * y0 + (f3 - 2 * f2 + f) * m0 +
                                    (-2 * f3 + 3 * f2) * y1 + (f3 - f2) * m1);
    }
    return out;
  }

  // The left (+N d_left) and the right (-N d_right) offset at v, which share B(v) and N(v).
  std::array<Vector2d, 2> offsets(int i, double v) const {
    const Vector2d c = eval(spans[i].b, v), n = left_normal(i, v);
    const std::array<double, 2> h = half_widths(i, v);
    return {c + h[0] * n, c + -h[1] * n};
  }

  // Both offsets at v and dp/dv there, by finite differences that stay inside the span (the
  // spline is only G1 across spans); `p` is offsets(i, v), shared with the side of the
  // difference that does not move (at a span's ends).
  struct End {
    std::array<Vector2d, 2> p, d;
  };
  End end(int i, double v, const std::array<Vector2d, 2>& p) const {
    const double h = 1e-6;
    const double a = std::max(0.0, v - h), b = std::min(1.0, v + h);
    const std::array<Vector2d, 2> pa = a == v ? p : offsets(i, a), pb = b == v ? p : offsets(i, b);
    return {p, {(pb[0] - pa[0]) / (b - a), (pb[1] - pa[1]) / (b - a)}};
  }
  End end(int i, double v) const { return end(i, v, offsets(i, v)); }

  // Hermite cubics matching the offsets' ends and end derivatives on [v0, v1]: left, right.
  static std::array<Cubic, 2> hermites(double v0, double v1, const End& e0, const End& e1) {
    const double third = (v1 - v0) / 3;
    std::array<Cubic, 2> out;
    for (int s = 0; s < 2; ++s)
      out[s] = {e0.p[s], e0.p[s] + e0.d[s] * third, e1.p[s] - e1.d[s] * third, e1.p[s]};
    return out;
  }
};

// A piece of the band: the left and right outline cubics over [v0, v1] of one span, both in the
// root-to-tip direction.
struct Piece {
  int span;
  double v0, v1;
  Cubic left, right;
};

// Fits [v0, v1] of a span, whose ends' offsets and derivatives are e0 and e1, splitting it in
// halves until five check points are within the tolerance; a split's middle is the check point
// at 1/2 (both are exact: the v's are dyadic), so each end is evaluated once.
void fit_pieces(const Extruder& ex, int span, double v0, double v1, const Extruder::End& e0,
                const Extruder::End& e1, int level, std::vector<Piece>& out) {
  const std::array<Cubic, 2> sides = Extruder::hermites(v0, v1, e0, e1);
  if (level < 12) {
    std::array<Vector2d, 2> middle;
    bool have_middle = false;
    for (double q : {0.1, 0.3, 0.5, 0.7, 0.9}) {
      const std::array<Vector2d, 2> exact = ex.offsets(span, v0 + (v1 - v0) * q);
      if (q == 0.5) middle = exact, have_middle = true;
      if ((eval(sides[0], q) - exact[0]).norm() > ex.style.fit_tolerance_px ||
          (eval(sides[1], q) - exact[1]).norm() > ex.style.fit_tolerance_px) {
        const double mid = 0.5 * (v0 + v1);
        const Extruder::End em = have_middle ? ex.end(span, mid, middle) : ex.end(span, mid);
        fit_pieces(ex, span, v0, mid, e0, em, level + 1, out);
        fit_pieces(ex, span, mid, v1, em, e1, level + 1, out);
        return;
      }
    }
  }
  out.push_back({span, v0, v1, sides[0], sides[1]});
}

double squared_distance_to_segment(const Vector2d& p, const Vector2d& a, const Vector2d& b) {
  const Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double l = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + l * ab - p).squaredNorm();
}

// Douglas-Peucker on three polylines at once: a section stays if dropping it would move the
// left, right or centre polyline by more than `tolerance`. The ends always stay. A section's
// distance, the largest of its three, is the root of the largest square; the root is taken only
// where the square passes the worst one so far (roots are monotone: the same sections win).
void simplify(const std::vector<Section>& dense, double tolerance, std::vector<char>& keep,
              std::vector<std::pair<int, int>>& stack, std::vector<Section>& out) {
  // The largest square whose root is within the tolerance.
  double within = tolerance * tolerance;
  while (within > 0 && std::sqrt(within) > tolerance) within = std::nextafter(within, 0.0);
  while (within < INFINITY && std::sqrt(std::nextafter(within, INFINITY)) <= tolerance)
    within = std::nextafter(within, INFINITY);
  const int n = int(dense.size());
  keep.assign(n, 0);
  keep[0] = keep[n - 1] = 1;
  int kept = 2;
  stack.assign(1, {0, n - 1});
  while (!stack.empty()) {
    const auto [a, b] = stack.back();
    stack.pop_back();
    double worst = tolerance, worst_square = within;
    int split = -1;
    const Section &sa = dense[a], &sb = dense[b];
    for (int j = a + 1; j < b; ++j) {
      const Section& s = dense[j];
      const double square = std::max({squared_distance_to_segment(s.left, sa.left, sb.left),
                                      squared_distance_to_segment(s.right, sa.right, sb.right),
                                      squared_distance_to_segment(s.centre, sa.centre, sb.centre)});
      if (square <= worst_square) continue;
      const double d = std::sqrt(square);
      if (d > worst) worst = d, split = j;
      worst_square = square;
    }
    if (split < 0) continue;
    keep[split] = 1;
    ++kept;
    stack.push_back({a, split});
    stack.push_back({split, b});
  }
  out.reserve(kept);
  for (int j = 0; j < n; ++j)
    if (keep[j]) out.push_back(dense[j]);
}

// The scratch arrays of one wisp's construction, shared by the wisps of a frame so that a wisp
// allocates only what it returns.
struct Workspace {
  std::vector<int> kept;
  std::vector<CentrePoint> points;
  std::vector<Vector2d> pixels;
  std::vector<Span> spans;
  ExtruderArrays extruder;
  std::vector<Piece> pieces;
  std::vector<Section> dense;
  std::vector<char> keep;
  std::vector<std::pair<int, int>> stack;
};

std::optional<Wisp> build_wisp(const sim::ProjectedStrand& strand, double focal_px,
                               const WispStyle& style, Workspace& ws);

}  // namespace

const char* to_string(Side side) {
  switch (side) {
    case Side::Left:
      return "left";
    case Side::Tip:
      return "tip";
    case Side::Right:
      return "right";
    case Side::Root:
      return "root";
  }
  return "?";
}

void validate(const WispStyle& style) {
  auto positive = [](double v, const char* name) {
    if (!(v > 0) || std::isnan(v))
      throw std::invalid_argument(std::string("wisp style: ") + name + " must be > 0, got " +
                                  std::to_string(v));
  };
  positive(style.width, "width");
  if (!std::isfinite(style.width)) throw std::invalid_argument("wisp style: width is not finite");
  positive(style.max_width_px, "max_width_px");
  positive(style.curvature_clamp, "curvature_clamp");
  positive(style.fit_tolerance_px, "fit_tolerance_px");
  positive(style.flatten_tolerance_px, "flatten_tolerance_px");
  positive(style.max_coordinate_px, "max_coordinate_px");
  if (style.max_pieces_per_cubic < 1 || style.max_pieces_per_cubic > 4096)
    throw std::invalid_argument("wisp style: max_pieces_per_cubic must be in [1,4096]");
  if (!(style.root_taper >= 0 && style.root_taper <= 1))
    throw std::invalid_argument("wisp style: root_taper must be in [0, 1]");
  if (!(style.merge_distance_px >= 0))
    throw std::invalid_argument("wisp style: merge_distance_px must be >= 0");
  validate(style.profile);
}

namespace {

std::optional<Wisp> build_wisp(const sim::ProjectedStrand& strand, double focal_px,
                               const WispStyle& style, Workspace& ws) {
  check_strand(strand);
  const int samples = int(strand.pixel.size());
  if (samples < 2) return std::nullopt;
  const auto [first, last] = usable_run(strand, style);
  if (last <= first) return std::nullopt;

  // Keep samples at least merge_distance apart; the tip sample always survives.
  std::vector<int>& kept = ws.kept;
  kept.assign(1, first);
  for (int i = first + 1; i <= last; ++i) {
    if ((strand.pixel[i] - strand.pixel[kept.back()]).norm() > style.merge_distance_px)
      kept.push_back(i);
    else if (i == last && kept.size() > 1)
      kept.back() = i;
  }
  if (kept.size() < 2) return std::nullopt;

  Wisp w;
  w.strand = strand.id;
  w.first_sample = first;
  w.last_sample = last;
  std::vector<CentrePoint>& points = ws.points;
  points.clear();
  for (int i : kept)
    points.push_back({strand.pixel[i], strand.depth[i], double(i) / (samples - 1),
                      strand.tangent.empty() ? Vector3d::Zero() : strand.tangent[i],
                      strand.width.empty() ? -1.0 : strand.width[i]});
  if (!strand.width.empty()) square_caps(points, focal_px, style);
  std::vector<Vector2d>& pixels = ws.pixels;
  pixels.clear();
  for (const CentrePoint& p : points) pixels.push_back(p.pixel);
  CentreSpline& c = w.centre;
  c.points = catmull_rom_path(pixels).points;
  const int k = c.piece_count();

  std::vector<Span>& spans = ws.spans;
  spans.clear();
  c.depth.reserve(3 * k + 1);
  c.tangent.reserve(3 * k + 1);
  c.strand_u.reserve(3 * k + 1);
  for (int s = 0; s < k; ++s) {
    const CentrePoint &a = points[s], &b = points[s + 1];
    spans.push_back({c.piece(s), a.depth, b.depth, a.u, b.u, a.width, b.width});
    for (int j = 0; j < 3; ++j) {
      const double f = j / 3.0;
      c.depth.push_back(a.depth + (b.depth - a.depth) * f);
      const Vector3d t = (1 - f) * a.tangent + f * b.tangent;
      c.tangent.push_back(t.norm() > 0 ? Vector3d(t.normalized()) : t);
      c.strand_u.push_back(a.u + (b.u - a.u) * f);
    }
  }
  c.depth.push_back(points.back().depth);
  c.tangent.push_back(points.back().tangent);
  c.strand_u.push_back(points.back().u);

  const Extruder ex(spans, style, focal_px, ws.extruder);
  w.half_width_left.reserve(k + 1);
  w.half_width_right.reserve(k + 1);
  for (int s = 0; s <= k; ++s) {
    const int span = std::min(s, k - 1);
    const double v = s < k ? 0.0 : 1.0;
    const std::array<double, 2> h = ex.half_widths(span, v);
    w.half_width_left.push_back(h[0]);
    w.half_width_right.push_back(h[1]);
  }

  std::vector<Piece>& pieces = ws.pieces;
  pieces.clear();
  for (int s = 0; s < k; ++s) fit_pieces(ex, s, 0, 1, ex.end(s, 0), ex.end(s, 1), 0, pieces);
  const int m = int(pieces.size());
  const bool tip_cap = pieces.back().left[3] != pieces.back().right[3];
  const bool root_cap = pieces.front().left[0] != pieces.front().right[0];
  const int cubic_count = 2 * m + tip_cap + root_cap;

  // The outline path: left pieces, tip cap, right pieces reversed, root cap.
  Outline& o = w.outline;
  o.points.reserve(3 * cubic_count + 1);
  o.t.reserve(3 * cubic_count + 1);
  o.depth.reserve(3 * cubic_count + 1);
  o.side.reserve(cubic_count);
  auto t_of = [&](const Piece& p, double q) { return (p.span + p.v0 + (p.v1 - p.v0) * q) / k; };
  auto z_of = [&](const Piece& p, double q) { return ex.depth(p.span, p.v0 + (p.v1 - p.v0) * q); };
  auto add_cubic = [&](const Cubic& cubic, Side side, double t0, double t1, double z0, double z1) {
    if (o.points.empty()) {
      o.t.push_back(t0);
      o.depth.push_back(z0);
    }
    o.append(cubic);
    for (int j = 1; j <= 3; ++j) {
      o.t.push_back(t0 + (t1 - t0) * j / 3);
      o.depth.push_back(z0 + (z1 - z0) * j / 3);
    }
    o.side.push_back(side);
  };
  for (const Piece& p : pieces)
    add_cubic(p.left, Side::Left, t_of(p, 0), t_of(p, 1), z_of(p, 0), z_of(p, 1));
  const double z_tip = spans.back().z1, z_root = spans.front().z0;
  if (tip_cap)
    add_cubic(line_cubic(pieces.back().left[3], pieces.back().right[3]), Side::Tip, 1, 1, z_tip,
              z_tip);
  for (int j = m - 1; j >= 0; --j) {
    const Piece& p = pieces[j];
    add_cubic(reversed(p.right), Side::Right, t_of(p, 1), t_of(p, 0), z_of(p, 1), z_of(p, 0));
  }
  if (root_cap)
    add_cubic(line_cubic(pieces.front().right[0], pieces.front().left[0]), Side::Root, 0, 0, z_root,
              z_root);

  // The band sections: dense uniform steps per piece within a quarter of the tolerance, then
  // thinned by Douglas-Peucker on the left, right and centre polylines together (the remaining
  // three quarters), so straight stretches cost few segments and tight curls many.
  std::vector<Section>& dense = ws.dense;
  dense.clear();
  const double dense_tolerance = 0.25 * style.flatten_tolerance_px;
  for (int j = 0; j < m; ++j) {
    const Piece& p = pieces[j];
    const int n = std::max(flatten_pieces(p.left, dense_tolerance, style.max_pieces_per_cubic),
                           flatten_pieces(p.right, dense_tolerance, style.max_pieces_per_cubic));
    const int right_index = m + tip_cap + (m - 1 - j);
    for (int i = 0; i < n + (j == m - 1); ++i) {
      const double q = double(i) / n;
      const double v = p.v0 + (p.v1 - p.v0) * q;
      Section sec;
      sec.t = t_of(p, q);
      sec.depth = ex.depth(p.span, v);
      sec.centre = eval(spans[p.span].b, v);
      sec.left = eval(p.left, q);
      sec.right = eval(p.right, q);
      sec.s_left = (j + q) / cubic_count;
      sec.s_right = (right_index + 1 - q) / cubic_count;
      dense.push_back(sec);
    }
  }
  simplify(dense, 0.75 * style.flatten_tolerance_px, ws.keep, ws.stack, w.sections);
  w.bounds.setEmpty();
  for (const Section& s : w.sections) {
    w.bounds.extend(s.left);
    w.bounds.extend(s.right);
  }
  return w;
}

}  // namespace

std::vector<Wisp> build_wisps(const sim::ProjectedFrame& frame, const WispStyle& style) {
  validate(style);
  if (!std::isfinite(frame.focal_px) || frame.focal_px <= 0)
    throw std::invalid_argument("projected frame " + std::to_string(frame.frame) +
                                ": focal_px must be finite and > 0");
  std::vector<Wisp> wisps;
  wisps.reserve(frame.strands.size());
  Workspace ws;
  for (const sim::ProjectedStrand& strand : frame.strands)
    if (auto w = build_wisp(strand, frame.focal_px, style, ws)) wisps.push_back(std::move(*w));
  return wisps;
}

std::optional<Wisp> build_wisp(const sim::ProjectedStrand& strand, double focal_px,
                               const WispStyle& style) {
  Workspace ws;
  return build_wisp(strand, focal_px, style, ws);
}

std::vector<OutlineVertex> outline_polygon(const Wisp& w) {
  return outline_polygon(w, 0, int(w.sections.size()) - 1);
}

std::vector<OutlineVertex> outline_polygon(const Wisp& w, int first, int last) {
  std::vector<OutlineVertex> poly;
  auto add = [&](const Vector2d& p, double s, double t, double depth, Side side) {
    if (!poly.empty() && poly.back().p == p) {
      poly.back().side = side;  // the zero-length edge disappears; the next edge keeps its side
      return;
    }
    poly.push_back({p, s, t, depth, side});
  };
  const auto& sec = w.sections;
  const bool tip_cap = sec[last].left != sec[last].right;
  for (int i = first; i < last; ++i)
    add(sec[i].left, sec[i].s_left, sec[i].t, sec[i].depth, Side::Left);
  add(sec[last].left, sec[last].s_left, sec[last].t, sec[last].depth,
      tip_cap ? Side::Tip : Side::Right);
  for (int i = last - (tip_cap ? 0 : 1); i > first; --i)
    add(sec[i].right, sec[i].s_right, sec[i].t, sec[i].depth, Side::Right);
  add(sec[first].right, sec[first].s_right, sec[first].t, sec[first].depth, Side::Root);
  if (poly.size() > 1 && poly.back().p == poly.front().p) poly.pop_back();
  return poly;
}

}  // namespace wisp::vector
