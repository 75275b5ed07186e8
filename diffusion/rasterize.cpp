// Rasterizer: curve crossings of pixel links -> cut links, fixed colours, gradient field.
// The sampling rule is documented in rasterize.hpp.
#include "diffusion/rasterize.hpp"

#include <cmath>
#include <limits>

#include "diffusion/bezier.hpp"

namespace wisp::diffusion {
namespace {

struct Rasterizer {
  Problem& problem;
  std::vector<float> claim_distance;  // W*H: distance of the nearest Dirichlet claim so far
  std::vector<float> wx, wy;          // gradient field of gradient curves (allocated on demand)

  int width() const { return problem.width; }
  int height() const { return problem.height; }

  bool inside(int x, int y) const { return x >= 0 && y >= 0 && x < width() && y < height(); }

  // Pixel (x,y) is on `side_is_left` of the curve at parameter t, `distance` from the crossing.
  void claim(const DiffusionCurve& c, int x, int y, bool side_is_left, double t, float distance) {
    if (!inside(x, y)) return;
    if ((side_is_left ? c.left_boundary : c.right_boundary) != Boundary::Dirichlet) return;
    const size_t i = problem.index(x, y);
    if (distance >= claim_distance[i]) return;
    claim_distance[i] = distance;
    problem.fixed[i] = 1;
    const Color col = color_at(side_is_left ? c.left : c.right, t);
    const size_t n = problem.pixel_count();
    for (int k = 0; k < 3; ++k) problem.value[k * n + i] = col[k];
    if (problem.channels == 4) problem.value[3 * n + i] = blur_at(c.blur, t);
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
  // along it; `a_is_left` says which side of the curve a lies on.
  void crossing(const DiffusionCurve& c, int ax, int ay, int dx, int dy, double f, bool a_is_left,
                double t) {
    const int bx = ax + dx, by = ay + dy;
    const bool link_inside = inside(ax, ay) && inside(bx, by);
    if (c.gradient_only) {
      if (link_inside) add_jump(c, dx ? wx : wy, problem.index(ax, ay), a_is_left, t);
      return;
    }
    if (link_inside) problem.links[problem.index(ax, ay)] &= dx ? ~kOpenEast : ~kOpenSouth;
    claim(c, ax, ay, a_is_left, t, float(f));
    claim(c, bx, by, !a_is_left, t, float(1.0 - f));
  }

  bool active(const DiffusionCurve& c, double t) const {
    if (c.active.empty()) return true;
    for (const auto& [t0, t1] : c.active)
      if (t >= t0 && t <= t1) return true;
    return false;
  }

  // All crossings of one polyline edge with the lines through pixel centres.
  void edge(const DiffusionCurve& c, const PathSample& s0, const PathSample& s1) {
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
        crossing(c, int(fx), j, 1, 0, x - 0.5 - fx, d.y() > 0, t);
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
        crossing(c, i, int(fy), 0, 1, y - 0.5 - fy, d.x() < 0, t);
      }
    }
  }
};

}  // namespace

Problem rasterize(const std::vector<DiffusionCurve>& curves, int width, int height,
                  const RasterizeOptions& options) {
  Problem problem = make_open_problem(width, height, options.blur_channel ? 4 : 3);
  Rasterizer r{problem,
               std::vector<float>(problem.pixel_count(), std::numeric_limits<float>::infinity()),
               {},
               {}};
  for (const DiffusionCurve& c : curves) {
    const std::vector<PathSample> poly = flatten(c, options.flatten_tolerance);
    for (size_t k = 1; k < poly.size(); ++k) r.edge(c, poly[k - 1], poly[k]);
  }
  if (!r.wx.empty() || !r.wy.empty()) {
    const size_t n = problem.pixel_count() * problem.channels;
    r.wx.resize(n, 0.0f);
    r.wy.resize(n, 0.0f);
    add_gradient_field(problem, r.wx, r.wy);
  }
  return problem;
}

}  // namespace wisp::diffusion
