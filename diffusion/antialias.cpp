// Anti-aliasing of solved images by sub-samples that reach pixel centres (see antialias.hpp).
//
// The active curves are flattened into segments and binned into the pixels they pass through
// (a grid walk, so long straight segments cost their length, not their bounding box). A sub-sample
// of pixel p only ever looks at the centres of p and its eight neighbours, and the straight path
// to any of them stays inside their 3 x 3 block, so the segments binned in that block are all
// that can separate them. Pixels are independent: rows run in parallel and the result does not
// depend on the thread count.
#include "diffusion/antialias.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "diffusion/bezier.hpp"

namespace wisp::diffusion {
namespace {

using Eigen::Vector2d;

// A piece of an active curve, with the curve's parameter at its two ends.
struct Segment {
  Vector2d a, b;
  int curve;
  double ta, tb;
};

double cross(const Vector2d& u, const Vector2d& v) {
  return u.x() * v.y() - u.y() * v.x();
}

// The active parts of every curve as segments of its flattening (the rasterizer's polyline).
std::vector<Segment> active_segments(const std::vector<DiffusionCurve>& curves, double tolerance) {
  std::vector<Segment> out;
  for (size_t c = 0; c < curves.size(); ++c) {
    const DiffusionCurve& curve = curves[c];
    const std::vector<PathSample> poly = flatten(curve, tolerance);
    for (size_t k = 1; k < poly.size(); ++k) {
      const PathSample &s0 = poly[k - 1], &s1 = poly[k];
      if (curve.active.empty()) {
        out.push_back({s0.p, s1.p, int(c), s0.t, s1.t});
        continue;
      }
      // The parts of [s0.t, s1.t] inside active intervals; t is linear along the segment.
      const double span = s1.t - s0.t;
      for (const auto& [t0, t1] : curve.active) {
        const double u0 = std::max(s0.t, t0), u1 = std::min(s1.t, t1);
        if (u1 < u0 || (u1 == u0 && span > 0)) continue;
        const double f0 = span > 0 ? (u0 - s0.t) / span : 0, f1 = span > 0 ? (u1 - s0.t) / span : 1;
        out.push_back({s0.p + f0 * (s1.p - s0.p), s0.p + f1 * (s1.p - s0.p), int(c), u0, u1});
      }
    }
  }
  return out;
}

// Clips the segment a-b to the box [lo, hi]^2 (Liang-Barsky); false when nothing is left.
bool clip(Vector2d& a, Vector2d& b, const Vector2d& lo, const Vector2d& hi) {
  double t0 = 0, t1 = 1;
  const Vector2d d = b - a;
  for (int axis = 0; axis < 2; ++axis) {
    if (d[axis] == 0) {
      if (a[axis] < lo[axis] || a[axis] > hi[axis]) return false;
      continue;
    }
    double ta = (lo[axis] - a[axis]) / d[axis], tb = (hi[axis] - a[axis]) / d[axis];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  const Vector2d a0 = a;
  a = a0 + t0 * d;
  b = a0 + t1 * d;
  return true;
}

// Calls visit(x, y) for every pixel of the window that the segment passes through (Amanatides and
// Woo's grid walk), in image coordinates.
template <class Visit>
void pixels_along(Vector2d a, Vector2d b, const PixelWindow& box, Visit&& visit) {
  const int x0 = box.x, y0 = box.y, x1 = box.x + box.width - 1, y1 = box.y + box.height - 1;
  if (!clip(a, b, Vector2d(x0, y0), Vector2d(x1 + 1, y1 + 1))) return;
  const auto cell = [](double v, int lo, int hi) { return std::clamp(int(std::floor(v)), lo, hi); };
  int x = cell(a.x(), x0, x1), y = cell(a.y(), y0, y1);
  const int xe = cell(b.x(), x0, x1), ye = cell(b.y(), y0, y1);
  const Vector2d d = b - a;
  const int sx = d.x() > 0 ? 1 : -1, sy = d.y() > 0 ? 1 : -1;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  double next_x = d.x() != 0 ? ((sx > 0 ? x + 1 : x) - a.x()) / d.x() : kInf;
  double next_y = d.y() != 0 ? ((sy > 0 ? y + 1 : y) - a.y()) / d.y() : kInf;
  const double step_x = d.x() != 0 ? sx / d.x() : kInf, step_y = d.y() != 0 ? sy / d.y() : kInf;
  const int steps = std::abs(xe - x) + std::abs(ye - y);
  for (int k = 0;; ++k) {
    visit(x, y);
    if (k == steps) break;
    if (next_x < next_y) {
      next_x += step_x;
      x = std::clamp(x + sx, x0, x1);
    } else {
      next_y += step_y;
      y = std::clamp(y + sy, y0, y1);
    }
  }
}

// Whether the closed segments p-q and a-b meet. Touching counts: a path through a curve's vertex
// or along it is blocked, so nothing leaks through a joint of the polyline.
bool meet(const Vector2d& p, const Vector2d& q, const Vector2d& a, const Vector2d& b) {
  const double d1 = cross(b - a, p - a), d2 = cross(b - a, q - a);
  const double d3 = cross(q - p, a - p), d4 = cross(q - p, b - p);
  if ((d1 > 0 && d2 > 0) || (d1 < 0 && d2 < 0) || (d3 > 0 && d4 > 0) || (d3 < 0 && d4 < 0))
    return false;
  if (d1 == 0 && d2 == 0 && d3 == 0 && d4 == 0) {  // collinear: overlap of the projections
    const Vector2d dir = (q - p).squaredNorm() > 0 ? Vector2d(q - p) : Vector2d(b - a);
    const double p0 = dir.dot(p), p1 = dir.dot(q), a0 = dir.dot(a), a1 = dir.dot(b);
    return std::max(std::min(p0, p1), std::min(a0, a1)) <=
           std::min(std::max(p0, p1), std::max(a0, a1));
  }
  return true;
}

// Per pixel of `box`, the segments that pass through it (compressed rows: those of the pixel
// with index p = bin(x, y) are index[first[p]] .. index[first[p + 1] - 1]).
struct SegmentBins {
  PixelWindow box;
  std::vector<int> first, index;

  size_t bin(int x, int y) const { return size_t(y - box.y) * box.width + (x - box.x); }
};

// `box` holds every segment whole (see segments_box), so clipping to it leaves each as clipping
// to the image would: the bins are the image's, kept only where segments are.
SegmentBins bin_segments(const std::vector<Segment>& segments, const PixelWindow& box) {
  SegmentBins bins;
  bins.box = box;
  bins.first.assign(box.pixel_count() + 1, 0);
  for (const Segment& s : segments)
    pixels_along(s.a, s.b, box, [&](int x, int y) { ++bins.first[bins.bin(x, y) + 1]; });
  for (size_t i = 1; i < bins.first.size(); ++i) bins.first[i] += bins.first[i - 1];
  bins.index.resize(bins.first.back());
  std::vector<int> fill(bins.first.begin(), bins.first.end() - 1);
  for (size_t k = 0; k < segments.size(); ++k)
    pixels_along(segments[k].a, segments[k].b, box,
                 [&](int x, int y) { bins.index[fill[bins.bin(x, y)]++] = int(k); });
  return bins;
}

// The pixels of the image that the segments' boxes reach (each pixel whole), where antialias
// works: a window of a few hair strands' size instead of the image.
PixelWindow segments_box(const std::vector<const std::vector<Segment>*>& lists, int width,
                         int height) {
  Eigen::AlignedBox2d box;
  for (const std::vector<Segment>* list : lists)
    for (const Segment& s : *list) box.extend(s.a), box.extend(s.b);
  if (box.isEmpty()) return {};
  // floor(max) + 1, not ceil(max): a segment ending on a pixel's edge counts that pixel.
  const double x0 = std::max(0.0, std::floor(box.min().x()));
  const double y0 = std::max(0.0, std::floor(box.min().y()));
  const double x1 = std::min(double(width), std::floor(box.max().x()) + 1);
  const double y1 = std::min(double(height), std::floor(box.max().y()) + 1);
  if (!(x0 < x1 && y0 < y1)) return {};
  return {int(x0), int(y0), int(x1 - x0), int(y1 - y0)};
}

// The pixel's own centre and its eight neighbours' as offsets, nearest first from sub-sample s
// (ties in a fixed order), for each of the n x n sub-sample positions.
std::vector<std::array<std::array<int, 2>, 9>> neighbour_orders(int n) {
  std::vector<std::array<std::array<int, 2>, 9>> orders(size_t(n) * n);
  for (int sy = 0; sy < n; ++sy)
    for (int sx = 0; sx < n; ++sx) {
      const Vector2d q((sx + 0.5) / n, (sy + 0.5) / n);
      std::array<std::array<int, 2>, 9>& o = orders[size_t(sy) * n + sx];
      for (int k = 0; k < 9; ++k) o[k] = {k % 3 - 1, k / 3 - 1};
      std::stable_sort(o.begin(), o.end(), [&](const auto& u, const auto& v) {
        return (Vector2d(u[0] + 0.5, u[1] + 0.5) - q).squaredNorm() <
               (Vector2d(v[0] + 0.5, v[1] + 0.5) - q).squaredNorm();
      });
    }
  return orders;
}

constexpr int kMaxSamples = 16 * 16;  // AntialiasOptions::samples is at most 16

// A segment near the pixel being re-sampled, copied out of the list (which is indexed and ordered
// like `local` below) so that the inner loops read contiguous memory.
struct LocalSegment {
  Vector2d a, b, d;  // d = b - a
  double len2;       // |d|^2
  int k, curve;      // index in the segment list, Segment::curve
};

// The point of the local segments nearest to a point: which segment, where along it, how far.
struct NearestPoint {
  const Segment* segment = nullptr;
  double along = 0, distance = std::numeric_limits<double>::infinity();
};

// The nearest point of the local segments (of curve `only_curve` alone, when it is not -1) to each
// of the points (qx[i], qy[i]), i < count: one pass over the segments for all of them, the points
// in the inner loop so that it vectorises. Its roundings are spelled out (the products summed
// unfused, a + f d one fused multiply-add where the CPU has it), as the Eigen expression it
// replaced computed them, so that pictures keep their bytes whatever the compiler contracts.
__attribute__((optimize("fp-contract=off"))) void nearest_points(
    const double* qx, const double* qy, int count, const std::vector<LocalSegment>& local,
    const std::vector<Segment>& segments, NearestPoint* out, int only_curve = -1) {
  double best2[kMaxSamples], along[kMaxSamples];
  int best[kMaxSamples];
  for (int s = 0; s < count; ++s)
    best2[s] = std::numeric_limits<double>::infinity(), best[s] = -1, along[s] = 0;
  for (int i = 0; i < int(local.size()); ++i) {
    const LocalSegment& g = local[size_t(i)];
    if (only_curve >= 0 && g.curve != only_curve) continue;
    const double ax = g.a.x(), ay = g.a.y(), dx = g.d.x(), dy = g.d.y(), len2 = g.len2;
    const bool flat = !(len2 > 0);
    for (int s = 0; s < count; ++s) {
      const double dot = (qx[s] - ax) * dx + (qy[s] - ay) * dy;
      const double f = flat ? 0.0 : std::clamp(dot / len2, 0.0, 1.0);
#if defined(__FMA__)  // where Eigen's a + f d is one fused multiply-add
      const double ex = std::fma(f, dx, ax) - qx[s], ey = std::fma(f, dy, ay) - qy[s];
#else
      const double ex = (ax + f * dx) - qx[s], ey = (ay + f * dy) - qy[s];
#endif
      const double dist2 = ex * ex + ey * ey;
      const bool nearer = dist2 < best2[s];
      best2[s] = nearer ? dist2 : best2[s];
      best[s] = nearer ? i : best[s];
      along[s] = nearer ? f : along[s];
    }
  }
  for (int s = 0; s < count; ++s) {
    out[s].segment = best[s] >= 0 ? &segments[local[size_t(best[s])].k] : nullptr;
    out[s].along = along[s];
    out[s].distance = std::sqrt(best2[s]);
  }
}

// The colour a curve imposes on the side of it that faces q at its point `at`, if that side is a
// Dirichlet boundary.
bool facing_colour(const std::vector<DiffusionCurve>& curves, const NearestPoint& at,
                   const Vector2d& q, Color& out) {
  const Segment& g = *at.segment;
  const DiffusionCurve& c = curves[g.curve];
  const bool left = cross(g.b - g.a, q - g.a) > 0;
  if (c.gradient_only || (left ? c.left_boundary : c.right_boundary) != Boundary::Dirichlet)
    return false;
  out = color_at(left ? c.left : c.right, g.ta + at.along * (g.tb - g.ta));
  return true;
}

// The region's ring edges as segments (curve -1), for binning like the curves.
std::vector<Segment> ring_segments(const std::vector<std::vector<Vector2d>>& rings) {
  std::vector<Segment> out;
  for (const auto& ring : rings)
    for (size_t k = 0; k < ring.size(); ++k)
      out.push_back({ring[k], ring[(k + 1) % ring.size()], -1, 0, 0});
  return out;
}

}  // namespace

AntialiasStats antialias(const std::vector<DiffusionCurve>& curves, int width, int height,
                         std::vector<float>& planes, const AntialiasRegion* region,
                         const AntialiasOptions& options) {
  const size_t n_pixels = size_t(width) * size_t(height);
  if (width <= 0 || height <= 0 || planes.size() < 3 * n_pixels)
    throw std::invalid_argument("antialias: image planes do not match the size");
  // The general form reads every colour before it writes any (below), so the planes can be both.
  const PixelWindow image{0, 0, width, height};
  return antialias(curves, width, height, planes, image, planes, image, region, options);
}

AntialiasStats antialias(const std::vector<DiffusionCurve>& curves, int width, int height,
                         const std::vector<float>& source, const PixelWindow& source_window,
                         std::vector<float>& planes, const PixelWindow& planes_window,
                         const AntialiasRegion* region, const AntialiasOptions& options) {
  const size_t n_pixels = size_t(width) * size_t(height);
  const PixelWindow &sw = source_window, &pw = planes_window;
  const size_t n_source = sw.pixel_count(), n_planes = pw.pixel_count();
  const auto inside_image = [&](const PixelWindow& w) {
    return w.x >= 0 && w.y >= 0 && w.width >= 0 && w.height >= 0 && w.x + w.width <= width &&
           w.y + w.height <= height;
  };
  if (width <= 0 || height <= 0 || planes.size() < 3 * n_planes || source.size() < 3 * n_source ||
      !inside_image(sw) || !inside_image(pw))
    throw std::invalid_argument("antialias: image planes do not match the size");
  if (region && region->centres.size() != n_pixels)
    throw std::invalid_argument("antialias: region does not match the image size");
  if (options.samples < 1 || options.samples > 16)
    throw std::invalid_argument("antialias: samples must be 1 to 16");

  AntialiasStats stats;
  const std::vector<Segment> segments = active_segments(curves, options.flatten_tolerance);
  stats.segments = long(segments.size());
  if (segments.empty()) return stats;
  const std::vector<Segment> edges = region ? ring_segments(region->rings) : std::vector<Segment>();
  const PixelWindow box = segments_box({&segments, &edges}, width, height);
  if (box.pixel_count() == 0) return stats;  // every segment outside the image
  const SegmentBins bins = bin_segments(segments, box);
  const SegmentBins edge_bins = region ? bin_segments(edges, box) : SegmentBins();
  // Whether sub-sample q of pixel p = (x, y) lies in the region: its centre's side, flipped by
  // every ring edge between q and the centre (both in p, so only the edges binned in p can cross).
  const auto inside = [&](const Vector2d& q, size_t p, int x, int y, const Vector2d& centre) {
    bool in = region->centres[p] != 0;
    const size_t b = edge_bins.bin(x, y);
    for (int k = edge_bins.first[b]; k < edge_bins.first[b + 1]; ++k)
      in ^= meet(q, centre, edges[edge_bins.index[k]].a, edges[edge_bins.index[k]].b);
    return in;
  };
  const int n = options.samples;
  const auto orders = neighbour_orders(n);
  // Sub-sample s of pixel (x, y) is at (x + offset_x[s], y + offset_y[s]).
  std::vector<double> offset_x(size_t(n) * n), offset_y(size_t(n) * n);
  for (int s = 0; s < n * n; ++s) offset_x[s] = (s % n + 0.5) / n, offset_y[s] = (s / n + 0.5) / n;

  // Each row's new colours, written once every row has been read: `source` may be `planes`.
  struct Resampled {
    int x;  // of the pixel; its row is the list's
    Color colour;
  };
  std::vector<std::vector<Resampled>> new_colours(static_cast<size_t>(height));
  std::vector<long> resampled(size_t(height), 0);
  const int box_x1 = box.x + box.width - 1, box_y1 = box.y + box.height - 1;
  tbb::parallel_for(
      tbb::blocked_range<int>(box.y, box_y1 + 1), [&](const tbb::blocked_range<int>& rows) {
        std::vector<int> local;
        std::vector<LocalSegment> near, blockers;
        std::vector<const Segment*> own;
        struct CentreDistance {
          size_t centre;
          int curve;
          double distance;
        };
        std::vector<CentreDistance> centre_distances;
        std::vector<double> qx(size_t(n) * n), qy(size_t(n) * n);
        std::vector<NearestPoint> nearest(size_t(n) * n);
        for (int y = rows.begin(); y < rows.end(); ++y)
          for (int x = box.x; x <= box_x1; ++x) {
            const size_t p = size_t(y) * width + x, b = bins.bin(x, y);
            if (bins.first[b] == bins.first[b + 1]) continue;
            // Every segment in the 3 x 3 block around p, once (the box holds every binned pixel).
            local.clear();
            for (int yy = std::max(box.y, y - 1); yy <= std::min(box_y1, y + 1); ++yy)
              for (int xx = std::max(box.x, x - 1); xx <= std::min(box_x1, x + 1); ++xx) {
                const size_t c = bins.bin(xx, yy);
                local.insert(local.end(), bins.index.begin() + bins.first[c],
                             bins.index.begin() + bins.first[c + 1]);
              }
            std::sort(local.begin(), local.end());
            local.erase(std::unique(local.begin(), local.end()), local.end());
            // The paths from a sub-sample to the centres it may take stay in the box from p's
            // corner (x - 1/2, y - 1/2) to (x + 3/2, y + 3/2): only segments whose own box meets it
            // can block one (with a margin far above rounding, so no test's answer changes).
            near.clear();
            blockers.clear();
            const Eigen::AlignedBox2d reach(Vector2d(x - 0.5 - 1e-6, y - 0.5 - 1e-6),
                                            Vector2d(x + 1.5 + 1e-6, y + 1.5 + 1e-6));
            for (int k : local) {
              const Segment& g = segments[k];
              const Vector2d d = g.b - g.a;
              near.push_back({g.a, g.b, d, d.squaredNorm(), k, g.curve});
              if (reach.intersects(Eigen::AlignedBox2d(g.a.cwiseMin(g.b), g.a.cwiseMax(g.b))))
                blockers.push_back(near.back());
            }

            // The path from a sub-sample to p's own centre lies inside p, at least half a
            // sub-sample spacing from its edges: only the segments binned in p can block it.
            own.clear();
            for (int k = bins.first[b]; k < bins.first[b + 1]; ++k)
              own.push_back(&segments[bins.index[k]]);

            // A centre's distance to a curve, once per pixel: its sub-samples share a few of them.
            centre_distances.clear();
            const auto centre_distance = [&](const Vector2d& centre, size_t c, int curve) {
              for (const CentreDistance& d : centre_distances)
                if (d.centre == c && d.curve == curve) return d.distance;
              NearestPoint at;
              nearest_points(&centre.x(), &centre.y(), 1, near, segments, &at, curve);
              const double d = at.distance;
              centre_distances.push_back({c, curve, d});
              return d;
            };

            // The colour at sub-sample q, reached from the centre of pixel c: the solved value
            // there, moved towards the colour of the nearest curve as q is nearer to it than the
            // centre is (the linear profile that the solve's boundary rule assumes along a link).
            const auto sample_colour = [&](const Vector2d& q, const NearestPoint& at,
                                           const Vector2d& centre, int cx, int cy) {
              const size_t c = size_t(cy) * width + cx;
              const int sx = cx - sw.x, sy = cy - sw.y;
              const size_t s = size_t(sy) * sw.width + sx;
              const Color solved =
                  sx >= 0 && sy >= 0 && sx < sw.width && sy < sw.height
                      ? Color(source[s], source[n_source + s], source[2 * n_source + s])
                      : Color::Zero();
              Color wall;
              if (!at.segment || !facing_colour(curves, at, q, wall)) return solved;
              const double from_centre = centre_distance(centre, c, at.segment->curve);
              if (!(from_centre > at.distance)) return solved;
              return Color(wall + (solved - wall) * float(at.distance / from_centre));
            };

            // The sub-samples and the nearest point of a curve to each.
            for (int s = 0; s < n * n; ++s) qx[s] = x + offset_x[s], qy[s] = y + offset_y[s];
            nearest_points(qx.data(), qy.data(), n * n, near, segments, nearest.data());
            Color sum = Color::Zero();
            int count = 0;
            for (int s = 0; s < n * n; ++s) {
              const Vector2d q(qx[s], qy[s]);
              if (region && !inside(q, p, x, y, Vector2d(x + 0.5, y + 0.5))) continue;  // not shown
              bool reached = false;
              for (const auto& [dx, dy] : orders[s]) {
                const int cx = x + dx, cy = y + dy;
                if (cx < 0 || cy < 0 || cx >= width || cy >= height) continue;
                const Vector2d centre(cx + 0.5, cy + 0.5);
                const bool blocked =
                    dx == 0 && dy == 0
                        ? std::any_of(own.begin(), own.end(),
                                      [&](const Segment* g) { return meet(q, centre, g->a, g->b); })
                        : std::any_of(blockers.begin(), blockers.end(), [&](const LocalSegment& g) {
                            return meet(q, centre, g.a, g.b);
                          });
                const size_t c = size_t(cy) * width + cx;
                // A centre outside the shown area holds no colour of it (the region's edge is not
                // always a curve: the head hides hair along its own outline).
                if (blocked || (region && !region->centres[c])) continue;
                reached = true;
                sum += sample_colour(q, nearest[s], centre, cx, cy);
                ++count;
                break;
              }
              if (reached) continue;
              // A sliver with no pixel centre: the side of the nearest curve that faces q.
              const NearestPoint& at = nearest[s];
              Color colour;
              if (at.segment && facing_colour(curves, at, q, colour)) {
                sum += colour;
                ++count;
              }
            }
            ++resampled[y];
            if (count == 0) continue;
            Color mean;
            for (int ch = 0; ch < 3; ++ch) mean[ch] = sum[ch] / count;
            new_colours[size_t(y)].push_back({x, mean});
          }
      });
  for (int y = pw.y; y < pw.y + pw.height; ++y)
    for (const Resampled& r : new_colours[size_t(y)]) {
      if (r.x < pw.x || r.x >= pw.x + pw.width) continue;
      const size_t i = size_t(y - pw.y) * pw.width + (r.x - pw.x);
      for (int ch = 0; ch < 3; ++ch) planes[ch * n_planes + i] = r.colour[ch];
    }
  for (long r : resampled) stats.pixels += r;
  return stats;
}

}  // namespace wisp::diffusion
