// Rasterizer: curve crossings of pixel links -> cut links, anchored or fixed colours, gradient
// field. The sampling rule is documented in rasterize.hpp.
//
// Claims are collected in a list as the curves are walked (memory in proportion to the crossings,
// not to the image), then sorted by pixel so that each pixel's nearest claim per link (or
// overall, in the first-order mode) is the first of its group; ties keep the drawing order.
#include "diffusion/rasterize.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "diffusion/bezier.hpp"

namespace wisp::diffusion {
namespace {

// A side of a curve faces a pixel across one of its links (Dirichlet sides; Neumann sides too
// when they are opaque).
struct Claim {
  std::uint64_t slot;  // pixel index * 4 + direction of the link (0 east, 1 west, 2 south, 3 north)
  double t;            // curve parameter at the crossing
  float distance;      // from the pixel centre to the crossing, in link lengths: theta
  std::uint32_t side;  // curve index * 2 + 1 for its left side, + 0 for its right
};

struct Rasterizer {
  const std::vector<DiffusionCurve>& curves;
  Problem& problem;
  const MeshRaster* meshes;
  NeumannSides neumann_sides;
  std::vector<Claim> claims;
  std::vector<float> wx, wy;  // gradient field of gradient curves (allocated on demand)

  int width() const { return problem.width; }
  int height() const { return problem.height; }

  bool inside(int x, int y) const { return x >= 0 && y >= 0 && x < width() && y < height(); }

  // Pixel (x,y) is on `side_is_left` of curve k at parameter t, `distance` from the crossing on
  // its link in `direction`.
  void claim(std::uint32_t k, int x, int y, int direction, bool side_is_left, double t,
             float distance) {
    const DiffusionCurve& c = curves[k];
    if (!inside(x, y)) return;
    const Boundary b = side_is_left ? c.left_boundary : c.right_boundary;
    if (b == Boundary::Neumann && neumann_sides == NeumannSides::Transparent) return;
    claims.push_back(
        {problem.index(x, y) * 4 + std::uint64_t(direction), t, distance, 2 * k + side_is_left});
  }

  // Colour jump across a gradient curve, from the pixel on `from_left` side to the other one.
  void add_jump(const DiffusionCurve& c, std::vector<float>& w, size_t link, bool from_left,
                double t) {
    const size_t n = problem.pixel_count();
    if (w.empty()) w.assign(n * problem.channels, 0.0f);
    const Color jump = color_at(c.right, t) - color_at(c.left, t);
    for (int k = 0; k < 3; ++k) w[k * n + link] += from_left ? jump[k] : -jump[k];
  }

  // A crossing of the link from pixel a = (ax,ay) to b = (ax+dx, ay+dy) at fraction f in [0,1)
  // along it; `a_is_left` says which side of curve k a lies on.
  void crossing(std::uint32_t k, int ax, int ay, int dx, int dy, double f, bool a_is_left,
                double t) {
    const DiffusionCurve& c = curves[k];
    const int bx = ax + dx, by = ay + dy;
    const bool link_inside = inside(ax, ay) && inside(bx, by);
    if (c.gradient_only) {
      if (link_inside) add_jump(c, dx ? wx : wy, problem.index(ax, ay), a_is_left, t);
      return;
    }
    if (link_inside) problem.links[problem.index(ax, ay)] &= dx ? ~kOpenEast : ~kOpenSouth;
    claim(k, ax, ay, dx ? 0 : 2, a_is_left, t, float(f));
    claim(k, bx, by, dx ? 1 : 3, !a_is_left, t, float(1.0 - f));
  }

  bool active(const DiffusionCurve& c, double t) const {
    if (c.active.empty()) return true;
    for (const auto& [t0, t1] : c.active)
      if (t >= t0 && t <= t1) return true;
    return false;
  }

  // All crossings of one polyline edge of curve k with the lines through pixel centres.
  void edge(std::uint32_t k, const PathSample& s0, const PathSample& s1) {
    const DiffusionCurve& c = curves[k];
    const Eigen::Vector2d p0 = s0.p, p1 = s1.p, d = p1 - p0;
    // Horizontal links lie on rows y = j + 0.5. Half-open rule: min <= y < max.
    if (d.y() != 0) {
      const double lo = std::min(p0.y(), p1.y()), hi = std::max(p0.y(), p1.y());
      const int j0 = std::max(0, int(std::ceil(lo - 0.5)));
      const int j1 = std::min(height() - 1, int(std::ceil(hi - 0.5)) - 1);
      for (int j = j0; j <= j1; ++j) {
        const double s = (j + 0.5 - p0.y()) / d.y();
        const double t = s0.t + s * (s1.t - s0.t);
        if (!active(c, t)) continue;
        const double x = p0.x() + s * d.x();
        const double fx = std::floor(x - 0.5);
        if (fx < -1 || fx > width() - 1) continue;
        // Pixel a = (i, j) lies towards -x of the crossing: on the left, (-d.y, d.x), iff d.y > 0.
        crossing(k, int(fx), j, 1, 0, x - 0.5 - fx, d.y() > 0, t);
      }
    }
    // Vertical links lie on columns x = i + 0.5.
    if (d.x() != 0) {
      const double lo = std::min(p0.x(), p1.x()), hi = std::max(p0.x(), p1.x());
      const int i0 = std::max(0, int(std::ceil(lo - 0.5)));
      const int i1 = std::min(width() - 1, int(std::ceil(hi - 0.5)) - 1);
      for (int i = i0; i <= i1; ++i) {
        const double s = (i + 0.5 - p0.x()) / d.x();
        const double t = s0.t + s * (s1.t - s0.t);
        if (!active(c, t)) continue;
        const double y = p0.y() + s * d.y();
        const double fy = std::floor(y - 0.5);
        if (fy < -1 || fy > height() - 1) continue;
        // Pixel a = (i, j) lies towards -y of the crossing: on the left iff d.x < 0.
        crossing(k, i, int(fy), 0, 1, y - 0.5 - fy, d.x() < 0, t);
      }
    }
  }

  bool is_neumann(const Claim& c) const {
    const DiffusionCurve& curve = curves[c.side / 2];
    return (c.side & 1 ? curve.left_boundary : curve.right_boundary) == Boundary::Neumann;
  }

  // The colour (and blur) of the side that makes the claim, at its crossing.
  std::array<double, 4> value(const Claim& c) const {
    const DiffusionCurve& curve = curves[c.side / 2];
    if (problem.channels == 1) return {blur_at(curve.blur, c.t), 0, 0, 0};
    const Color col = color_at(c.side & 1 ? curve.left : curve.right, c.t);
    return {col[0], col[1], col[2], problem.channels == 4 ? blur_at(curve.blur, c.t) : 0.0f};
  }

  void set_value(size_t pixel, const std::array<double, 4>& v) {
    const size_t n = problem.pixel_count();
    for (int k = 0; k < problem.channels; ++k) problem.value[k * n + pixel] = float(v[k]);
  }

  // Sorts the claims by pixel, then distance (then drawing order: the sort is stable), and calls
  // pixel_claims(pixel, first, last) for each pixel's run: claims[first] is its nearest claim,
  // and the first claim of each link direction in the run is the nearest on that link.
  template <class PixelClaims>
  void for_each_pixel(const PixelClaims& pixel_claims) {
    std::stable_sort(claims.begin(), claims.end(), [](const Claim& a, const Claim& b) {
      return a.slot / 4 != b.slot / 4 ? a.slot < b.slot : a.distance < b.distance;
    });
    for (size_t first = 0; first < claims.size();) {
      const size_t pixel = claims[first].slot / 4;
      size_t last = first + 1;
      while (last < claims.size() && claims[last].slot / 4 == pixel) ++last;
      pixel_claims(pixel, first, last);
      first = last;
    }
  }

  // The anchor of a mesh's own outline at a pixel of that mesh: the right-hand side gains what
  // the anchor term makes of the mesh colour, w (c - m_p), so that the mesh colour solves it.
  void mesh_anchor(size_t pixel, double w, const std::array<double, 4>& v) {
    const size_t n = problem.pixel_count();
    for (int c = 0; c < 3; ++c)
      problem.rhs[c * n + pixel] += float(w * (v[c] - meshes->planes[c * n + pixel]));
  }

  // Every free pixel of a mesh: the mesh colour's differences over its open links within the
  // same mesh.
  void mesh_laplacian() {
    const size_t n = problem.pixel_count();
    const auto link = [&](size_t p, size_t q) {
      if (meshes->owner[p] < 0 || meshes->owner[p] != meshes->owner[q]) return;
      for (int c = 0; c < 3; ++c) {
        const float d = meshes->planes[c * n + q] - meshes->planes[c * n + p];
        if (!problem.fixed[p]) problem.rhs[c * n + p] += d;
        if (!problem.fixed[q]) problem.rhs[c * n + q] -= d;
      }
    };
    for (int y = 0; y < height(); ++y)
      for (int x = 0; x < width(); ++x) {
        const size_t i = problem.index(x, y);
        if (problem.links[i] & kOpenEast) link(i, i + 1);
        if (problem.links[i] & kOpenSouth) link(i, i + size_t(width()));
      }
  }

  void fix(size_t pixel, const Claim& c) {
    problem.fixed[pixel] = 1;
    set_value(pixel, value(c));
  }

  // First order: a pixel is fixed to its nearest claim, unless that is a Neumann side.
  void fix_nearest() {
    for_each_pixel([&](size_t pixel, size_t first, size_t) {
      if (!is_neumann(claims[first])) fix(pixel, claims[first]);
    });
  }

  // Second order: the nearest claim on each of a pixel's links is an anchor at distance theta,
  // weighing 1/theta (problem.hpp), unless it is a Neumann side. A Dirichlet claim almost at the
  // centre fixes the pixel instead.
  void anchor() {
    for_each_pixel([&](size_t pixel, size_t first, size_t last) {
      if (claims[first].distance < kMinAnchorDistance && !is_neumann(claims[first]))
        return fix(pixel, claims[first]);
      double weight = 0;
      std::array<double, 4> sum{};
      bool seen[4] = {false, false, false, false};
      for (size_t k = first; k < last; ++k) {
        const int direction = int(claims[k].slot % 4);
        if (seen[direction]) continue;  // a farther claim on the same link: hidden
        seen[direction] = true;
        if (is_neumann(claims[k])) continue;  // the link's nearest side imposes no colour
        // Bounded like a fixing claim's: behind a Neumann claim at the centre (which fixes
        // nothing) a Dirichlet one on another link can lie at the centre too.
        const double w = 1.0 / std::max<double>(claims[k].distance, kMinAnchorDistance);
        const std::array<double, 4> v = value(claims[k]);
        weight += w;
        for (int c = 0; c < 4; ++c) sum[c] += w * v[c];
        if (meshes && curves[claims[k].side / 2].mesh_outline >= 0 &&
            curves[claims[k].side / 2].mesh_outline == meshes->owner[pixel])
          mesh_anchor(pixel, w, v);
      }
      if (weight == 0) return;  // every link's nearest side was Neumann: the pixel stays free
      problem.anchor_weight[pixel] = float(weight);
      for (double& v : sum) v /= weight;
      set_value(pixel, sum);
    });
  }
};

// The rasterizer of the public functions below: pixel (0,0) of the problem is pixel
// (origin.x, origin.y) of the curves' coordinates.
Problem rasterize_at(const std::vector<DiffusionCurve>& curves, const Eigen::Vector2d& origin,
                     int width, int height, const RasterizeOptions& options,
                     const MeshRaster* meshes) {
  Problem problem = make_open_problem(width, height,
                                      options.blur_only      ? 1
                                      : options.blur_channel ? 4
                                                             : 3);
  if (meshes && (meshes->width != width || meshes->height != height))
    throw std::invalid_argument("rasterize: the mesh coverage does not match the image size");
  if (meshes && options.blur_only)
    throw std::invalid_argument("rasterize: a blur map takes no gradient meshes");
  if (meshes) problem.rhs.assign(problem.pixel_count() * problem.channels, 0.0f);
  Rasterizer r{curves, problem, meshes, options.neumann, {}, {}, {}};
  for (std::uint32_t k = 0; k < curves.size(); ++k) {
    if (options.blur_only && curves[k].gradient_only) continue;
    std::vector<PathSample> poly = flatten(curves[k], options.flatten_tolerance);
    // Exact for an integer origin and coordinates within the window, so that the crossings are
    // the whole image's, shifted.
    for (PathSample& s : poly) s.p -= origin;
    for (size_t s = 1; s < poly.size(); ++s) r.edge(k, poly[s - 1], poly[s]);
  }
  if (options.dirichlet == DirichletSampling::NearestClaim)
    r.fix_nearest();
  else
    r.anchor();
  if (meshes) r.mesh_laplacian();
  if (!r.wx.empty() || !r.wy.empty()) {
    const size_t n = problem.pixel_count() * problem.channels;
    r.wx.resize(n, 0.0f);
    r.wy.resize(n, 0.0f);
    add_gradient_field(problem, r.wx, r.wy);
  }
  return problem;
}

}  // namespace

Problem rasterize(const std::vector<DiffusionCurve>& curves, int width, int height,
                  const RasterizeOptions& options, const MeshRaster* meshes) {
  return rasterize_at(curves, Eigen::Vector2d::Zero(), width, height, options, meshes);
}

Problem rasterize(const std::vector<DiffusionCurve>& curves, const PixelWindow& window,
                  const RasterizeOptions& options) {
  return rasterize_at(curves, Eigen::Vector2d(window.x, window.y), window.width, window.height,
                      options, nullptr);
}

PixelWindow curves_window(const std::vector<DiffusionCurve>& curves, int width, int height,
                          int margin, int align) {
  Eigen::AlignedBox2d box;
  for (const DiffusionCurve& c : curves)
    for (const Eigen::Vector2d& p : c.points) box.extend(p);
  if (box.isEmpty()) return {};
  const auto down = [align](double v) { return int(std::floor(v / align)) * align; };
  const auto up = [align](double v) { return int(std::ceil(v / align)) * align; };
  // Clamped in double first: a curve may reach far outside the image.
  const int x0 = std::max(0, down(std::max(-1.0, box.min().x() - margin)));
  const int y0 = std::max(0, down(std::max(-1.0, box.min().y() - margin)));
  const int x1 = std::min(width, up(std::min(width + 1.0, box.max().x() + margin)));
  const int y1 = std::min(height, up(std::min(height + 1.0, box.max().y() + margin)));
  if (x1 <= x0 || y1 <= y0) return {};
  return {x0, y0, x1 - x0, y1 - y0};
}

}  // namespace wisp::diffusion
