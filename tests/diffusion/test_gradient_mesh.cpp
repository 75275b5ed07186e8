// Gradient meshes and Poisson curves in the solve: a mesh alone solves to its own Ferguson
// colours, and a straight Poisson curve between two constant curves gives the analytic profile of
// a line dipole (two equal ramps and a step of the weight).
#include <catch2/catch.hpp>
#include <cmath>

#include "diffusion/gradient_mesh.hpp"
#include "diffusion/render.hpp"

using namespace wisp::diffusion;

namespace {

// Hermite basis, written out here so that the test does not use the code under test.
double h(int k, double s) {
  switch (k) {
    case 0:
      return 2 * s * s * s - 3 * s * s + 1;
    case 1:
      return -2 * s * s * s + 3 * s * s;
    case 2:
      return s * s * s - 2 * s * s + s;
    default:
      return s * s * s - s * s;
  }
}

// A 3 x 2 tile mesh on a regular grid (so its position map is affine: u, v follow x, y) whose
// vertex colours vary unevenly, so that the estimated colour tangents matter.
GradientMesh grid_mesh(double x0, double y0, double step) {
  GradientMesh m;
  m.rows = 2;
  m.cols = 3;
  for (int j = 0; j <= m.rows; ++j)
    for (int i = 0; i <= m.cols; ++i) {
      m.positions.emplace_back(x0 + step * i, y0 + step * j);
      m.colors.emplace_back(0.1f + 0.25f * i * i / 9.0f, 0.8f - 0.3f * j + 0.05f * i,
                            0.5f + 0.2f * float(std::sin(i + 2.0 * j)));
    }
  return m;
}

// The bicubic colour of that mesh at (x, y), from the definition: tangents are central
// differences in index space (one-sided at the border), twists are zero.
Eigen::Vector3d expected(const GradientMesh& m, double x0, double y0, double step, double x,
                         double y) {
  const double gu = (x - x0) / step, gv = (y - y0) / step;
  const int i = std::min(int(gu), m.cols - 1), j = std::min(int(gv), m.rows - 1);
  const double u = gu - i, v = gv - j;
  const auto c = [&](int a, int b) {
    return m.colors[size_t(b) * (m.cols + 1) + a].cast<double>();
  };
  const auto cu = [&](int a, int b) {
    const int a0 = std::max(0, a - 1), a1 = std::min(m.cols, a + 1);
    return Eigen::Vector3d((c(a1, b) - c(a0, b)) / (a1 - a0));
  };
  const auto cv = [&](int a, int b) {
    const int b0 = std::max(0, b - 1), b1 = std::min(m.rows, b + 1);
    return Eigen::Vector3d((c(a, b1) - c(a, b0)) / (b1 - b0));
  };
  Eigen::Vector3d out = Eigen::Vector3d::Zero();
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) {
      out += h(a, u) * h(b, v) * c(i + a, j + b);
      out += h(2 + a, u) * h(b, v) * cu(i + a, j + b);
      out += h(a, u) * h(2 + b, v) * cv(i + a, j + b);
    }
  return out;
}

}  // namespace

TEST_CASE("a gradient mesh alone solves to its bicubic colours", "[mesh]") {
  // Vertices on pixel centres; every pixel centre inside the mesh is a sample point.
  const double x0 = 6.5, y0 = 9.5, step = 16;
  Drawing d;
  d.width = d.height = 64;
  d.meshes = {grid_mesh(x0, y0, step)};
  for (const bool antialias : {false, true}) {
    RenderStats st;
    const Image im = render_drawing(d, 64, 64, {}, &st, antialias);
    CHECK(st.solver.converged);
    double worst = 0;
    int samples = 0;
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x) {
        const double cx = x + 0.5, cy = y + 0.5;
        // Pixels the outline crosses are anti-aliased with the (floating) outside: inner ones.
        if (cx < x0 + 1 || cy < y0 + 1 || cx > x0 + 3 * step - 1 || cy > y0 + 2 * step - 1)
          continue;
        const Eigen::Vector3d e = expected(d.meshes[0], x0, y0, step, cx, cy);
        for (int c = 0; c < 3; ++c)
          worst = std::max(worst, std::abs(im.planes[size_t(c) * 64 * 64 + y * 64 + x] - e[c]));
        ++samples;
      }
    INFO("antialias " << antialias << ", worst " << worst * 255 << "/255 over " << samples);
    CHECK(samples > 1000);
    CHECK(worst < 0.5 / 255);
  }
  // The inner vertices themselves hold their colours. (A pixel centre exactly on the outline
  // counts as outside, by the rasterizer's half-open rule.)
  const Image im = render_drawing(d, 64, 64, {}, nullptr, false);
  for (int j = 1; j < 2; ++j)
    for (int i = 1; i < 3; ++i) {
      const int x = int(x0 + step * i), y = int(y0 + step * j);
      for (int c = 0; c < 3; ++c)
        CHECK(im.planes[size_t(c) * 64 * 64 + y * 64 + x] ==
              Approx(d.meshes[0].colors[size_t(j) * 4 + i][c]).margin(1.0 / 255));
    }
}

TEST_CASE("mesh coverage inverts the Ferguson position map", "[mesh]") {
  // A bent mesh: positions on a wave, given tangents; every covered pixel's colour is the one at
  // the (u, v) whose position is its centre.
  GradientMesh m = grid_mesh(8, 8, 14);
  for (Eigen::Vector2d& p : m.positions) p.y() += 3 * std::sin(p.x() / 9);
  const MeshGeometry g = resolve_mesh(m, {64, 64}, {1, 1});
  const MeshRaster r = rasterize_meshes({g}, 64, 64);
  int covered = 0;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 3; ++i)
      for (double u : {0.2, 0.5, 0.8})
        for (double v : {0.3, 0.6}) {
          const Eigen::Vector2d p = mesh_position(g, i, j, u, v);
          const int x = int(p.x()), y = int(p.y());
          REQUIRE(r.owner[size_t(y) * 64 + x] == 0);
          ++covered;
          // The pixel centre is within a pixel of p: its colour is within that of the sample's.
          const Eigen::Vector3d c = mesh_color(g, i, j, u, v);
          CHECK(std::abs(r.planes[size_t(y) * 64 + x] - c[0]) < 0.03);
        }
  CHECK(covered == 36);
  CHECK(r.owner[0] == -1);
}

TEST_CASE("a Poisson curve gives the profile of a line dipole whatever the resolution",
          "[poisson]") {
  // small-usvg's scale: in a 1024 x 1024 drawing the step across the curve is the weight.
  // Constant curves at y = a and y = b hold 0.5; a straight Poisson curve at y0 crosses the whole
  // image travelling +x, so its right side is above it (smaller y). The exact solution has equal
  // slopes w / (b - a) on both sides and steps down by w from the right to the left side:
  //   u = 0.5 + s (y - a) above y0,  u = 0.5 + s (y - b) below, s = w / (b - a).
  const double a = 256, b = 768, y0 = 503.3, w = 0.2;
  Drawing d;
  d.width = d.height = 1024;
  for (const double y : {a, b}) {
    DiffusionCurve c;
    c.points = {{-8, y}, {340, y}, {690, y}, {1032, y}};
    c.left = c.right = {{0, Color::Constant(0.5f)}};
    d.curves.push_back(c);
  }
  PoissonCurve p;
  p.points = {{-8, y0}, {340, y0}, {690, y0}, {1032, y0}};
  p.weights = {{0, Color::Constant(float(w))}, {1, Color::Constant(float(w))}};
  d.poisson_curves = {p};
  // The link jumps are exactly the differences of that step, and the anchors of the constant
  // curves are exact for linear profiles: the discrete answer is the analytic one, to the
  // solver's tolerance, at every resolution.
  const double s = w / (b - a);
  for (const int size : {64, 256}) {
    const Image im = render_drawing(d, size, size, {}, nullptr, false);
    const double pitch = 1024.0 / size;
    double worst = 0;
    for (int y = 0; y < size; ++y) {
      const double cy = (y + 0.5) * pitch;
      if (cy <= a || cy >= b) continue;
      const double exact = 0.5 + s * (cy - (cy < y0 ? a : b));
      for (int x : {1, size / 2, size - 2})
        worst = std::max(worst, std::abs(double(im.planes[size_t(y) * size + x]) - exact));
    }
    INFO(size << " px: worst " << worst);
    CHECK(worst < 1e-4);
  }
}
