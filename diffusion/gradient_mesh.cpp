// Ferguson-patch evaluation, outlines and pixel coverage of gradient meshes (see
// gradient_mesh.hpp).
//
// Coverage: each tile's (u, v) square is cut into small quads (about two pixels on a side), each
// quad into two triangles; a pixel centre inside a triangle takes the (u, v) that the triangle
// interpolates, refined by Newton's method on position(u, v) = centre, and the colour there.
#include "diffusion/gradient_mesh.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>

namespace wisp::diffusion {
namespace {

// Cubic Hermite basis on [0,1] (value at 0, value at 1, slope at 0, slope at 1) and its
// derivative.
std::array<double, 4> hermite(double s) {
  const double s2 = s * s, s3 = s2 * s;
  return {2 * s3 - 3 * s2 + 1, -2 * s3 + 3 * s2, s3 - 2 * s2 + s, s3 - s2};
}
std::array<double, 4> hermite_slope(double s) {
  const double s2 = s * s;
  return {6 * s2 - 6 * s, -6 * s2 + 6 * s, 3 * s2 - 4 * s + 1, 3 * s2 - 2 * s};
}

// The Ferguson patch of tile (i, j): sum over a, b of hu[a] hv[b] Q[a][b], where Q holds the
// corner values, their v tangents (columns 2, 3) and u tangents (rows 2, 3), and zero twists.
template <class V>
V ferguson(const MeshGeometry& g, const std::vector<V>& val, const std::vector<V>& du,
           const std::vector<V>& dv, int i, int j, const std::array<double, 4>& hu,
           const std::array<double, 4>& hv) {
  const int stride = g.cols + 1;
  const size_t k00 = size_t(j) * stride + i, k10 = k00 + 1, k01 = k00 + stride, k11 = k01 + 1;
  const V q[4][4] = {{val[k00], val[k01], dv[k00], dv[k01]},
                     {val[k10], val[k11], dv[k10], dv[k11]},
                     {du[k00], du[k01], V::Zero(), V::Zero()},
                     {du[k10], du[k11], V::Zero(), V::Zero()}};
  V out = V::Zero();
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) out += (hu[a] * hv[b]) * q[a][b];
  return out;
}

// Central differences over the neighbours in index space, one-sided at the border.
template <class V>
void estimate_tangents(int rows, int cols, const std::vector<V>& val, std::vector<V>& du,
                       std::vector<V>& dv) {
  const int stride = cols + 1;
  du.assign(val.size(), V::Zero());
  dv.assign(val.size(), V::Zero());
  for (int j = 0; j <= rows; ++j)
    for (int i = 0; i <= cols; ++i) {
      const int i0 = std::max(0, i - 1), i1 = std::min(cols, i + 1);
      const int j0 = std::max(0, j - 1), j1 = std::min(rows, j + 1);
      const size_t k = size_t(j) * stride + i;
      du[k] = (val[size_t(j) * stride + i1] - val[size_t(j) * stride + i0]) / double(i1 - i0);
      dv[k] = (val[size_t(j1) * stride + i] - val[size_t(j0) * stride + i]) / double(j1 - j0);
    }
}

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

}  // namespace

MeshGeometry resolve_mesh(const GradientMesh& mesh, const Eigen::Vector2d& drawing_size,
                          const Eigen::Vector2d& scale) {
  MeshGeometry g;
  g.rows = mesh.rows;
  g.cols = mesh.cols;
  const Eigen::Vector2d to_pixels =
      mesh.normalized ? Eigen::Vector2d(drawing_size.cwiseProduct(scale)) : scale;
  const auto place = [&](const std::vector<Eigen::Vector2d>& in) {
    std::vector<Eigen::Vector2d> out(in.size());
    for (size_t k = 0; k < in.size(); ++k) out[k] = in[k].cwiseProduct(to_pixels);
    return out;
  };
  g.p = place(mesh.positions);
  if (mesh.tangents_u.empty()) {
    estimate_tangents(g.rows, g.cols, g.p, g.pu, g.pv);
  } else {
    g.pu = place(mesh.tangents_u);
    g.pv = place(mesh.tangents_v);
  }
  g.c.resize(mesh.colors.size());
  for (size_t k = 0; k < g.c.size(); ++k) g.c[k] = mesh.colors[k].cast<double>();
  estimate_tangents(g.rows, g.cols, g.c, g.cu, g.cv);
  return g;
}

Eigen::Vector2d mesh_position(const MeshGeometry& g, int i, int j, double u, double v) {
  return ferguson(g, g.p, g.pu, g.pv, i, j, hermite(u), hermite(v));
}

Eigen::Matrix2d mesh_jacobian(const MeshGeometry& g, int i, int j, double u, double v) {
  Eigen::Matrix2d m;
  m.col(0) = ferguson(g, g.p, g.pu, g.pv, i, j, hermite_slope(u), hermite(v));
  m.col(1) = ferguson(g, g.p, g.pu, g.pv, i, j, hermite(u), hermite_slope(v));
  return m;
}

Eigen::Vector3d mesh_color(const MeshGeometry& g, int i, int j, double u, double v) {
  return ferguson(g, g.c, g.cu, g.cv, i, j, hermite(u), hermite(v));
}

DiffusionCurve mesh_outline(const MeshGeometry& g, int index, int stops_per_edge) {
  // The edges in loop order, each as (vertex from, vertex to, along u?).
  struct Edge {
    int i0, j0, i1, j1;
  };
  std::vector<Edge> edges;
  for (int i = 0; i < g.cols; ++i) edges.push_back({i, g.rows, i + 1, g.rows});  // v = 1, +u
  for (int j = g.rows; j > 0; --j) edges.push_back({g.cols, j, g.cols, j - 1});  // u = 1, -v
  for (int i = g.cols; i > 0; --i) edges.push_back({i, 0, i - 1, 0});            // v = 0, -u
  for (int j = 0; j < g.rows; ++j) edges.push_back({0, j, 0, j + 1});            // u = 0, +v

  DiffusionCurve out;
  out.mesh_outline = index;
  out.left_boundary = Boundary::Neumann;
  out.right_boundary = Boundary::Dirichlet;
  const int stride = g.cols + 1;
  const double pieces = double(edges.size());
  for (size_t e = 0; e < edges.size(); ++e) {
    const Edge& d = edges[e];
    const size_t a = size_t(d.j0) * stride + d.i0, b = size_t(d.j1) * stride + d.i1;
    const bool along_u = d.j0 == d.j1;
    // Tangents along the direction of travel (the edge's own Hermite slopes).
    const double sign = along_u ? (d.i1 > d.i0 ? 1 : -1) : (d.j1 > d.j0 ? 1 : -1);
    const Eigen::Vector2d ta = sign * (along_u ? g.pu[a] : g.pv[a]);
    const Eigen::Vector2d tb = sign * (along_u ? g.pu[b] : g.pv[b]);
    out.append({g.p[a], g.p[a] + ta / 3, g.p[b] - tb / 3, g.p[b]});
    const Eigen::Vector3d ca = sign * (along_u ? g.cu[a] : g.cv[a]);
    const Eigen::Vector3d cb = sign * (along_u ? g.cu[b] : g.cv[b]);
    for (int s = (e == 0 ? 0 : 1); s <= stops_per_edge; ++s) {
      const double f = double(s) / stops_per_edge;
      const std::array<double, 4> h = hermite(f);
      const Eigen::Vector3d c = h[0] * g.c[a] + h[1] * g.c[b] + h[2] * ca + h[3] * cb;
      out.right.push_back({(double(e) + f) / pieces, c.cast<float>()});
    }
  }
  out.right.back().t = 1.0;  // exactly, whatever the rounding of the last division
  return out;
}

MeshRaster rasterize_meshes(const std::vector<MeshGeometry>& meshes, int width, int height) {
  MeshRaster r;
  r.width = width;
  r.height = height;
  const size_t n = size_t(width) * size_t(height);
  r.owner.assign(n, -1);
  r.planes.assign(3 * n, 0.0f);
  for (int m = 0; m < int(meshes.size()); ++m) {
    const MeshGeometry& g = meshes[m];
    const int stride = g.cols + 1;
    for (int j = 0; j < g.rows; ++j)
      for (int i = 0; i < g.cols; ++i) {
        // Sub-quads of about two pixels, from the extent of the tile's Bezier control net.
        Eigen::AlignedBox2d box;
        for (int dj = 0; dj < 2; ++dj)
          for (int di = 0; di < 2; ++di) {
            const size_t k = size_t(j + dj) * stride + i + di;
            box.extend(g.p[k]);
            box.extend(Eigen::Vector2d(g.p[k] + g.pu[k] / 3));
            box.extend(Eigen::Vector2d(g.p[k] - g.pu[k] / 3));
            box.extend(Eigen::Vector2d(g.p[k] + g.pv[k] / 3));
            box.extend(Eigen::Vector2d(g.p[k] - g.pv[k] / 3));
          }
        if (box.max().x() < 0 || box.max().y() < 0 || box.min().x() > width ||
            box.min().y() > height)
          continue;
        const int steps = std::clamp(int(std::ceil(box.sizes().maxCoeff() / 2)), 1, 4096);
        std::vector<Eigen::Vector2d> grid(size_t(steps + 1) * (steps + 1));
        for (int b = 0; b <= steps; ++b)
          for (int a = 0; a <= steps; ++a)
            grid[size_t(b) * (steps + 1) + a] =
                mesh_position(g, i, j, double(a) / steps, double(b) / steps);
        const auto cover = [&](const Eigen::Vector2d& x, const Eigen::Vector2d& uv) {
          // Newton on position(u, v) = x from the interpolated start, kept in the tile.
          Eigen::Vector2d w = uv;
          for (int it = 0; it < 8; ++it) {
            const Eigen::Vector2d res = mesh_position(g, i, j, w.x(), w.y()) - x;
            if (res.squaredNorm() < 1e-20) break;
            const Eigen::Matrix2d jac = mesh_jacobian(g, i, j, w.x(), w.y());
            if (std::abs(jac.determinant()) < 1e-12) break;
            w = (w - jac.inverse() * res).cwiseMax(0.0).cwiseMin(1.0);
          }
          return w;
        };
        for (int b = 0; b < steps; ++b)
          for (int a = 0; a < steps; ++a) {
            const auto at = [&](int da, int db) {
              return grid[size_t(b + db) * (steps + 1) + a + da];
            };
            const auto uv = [&](int da, int db) {
              return Eigen::Vector2d(double(a + da) / steps, double(b + db) / steps);
            };
            const std::array<std::array<int, 2>, 6> corners = {
                {{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}}};
            for (int t = 0; t < 2; ++t) {
              const auto& c0 = corners[3 * t];
              const auto& c1 = corners[3 * t + 1];
              const auto& c2 = corners[3 * t + 2];
              const Eigen::Vector2d p0 = at(c0[0], c0[1]), p1 = at(c1[0], c1[1]),
                                    p2 = at(c2[0], c2[1]);
              const double area = cross(p1 - p0, p2 - p0);
              if (area == 0) continue;
              const double lo_x = std::min({p0.x(), p1.x(), p2.x()});
              const double hi_x = std::max({p0.x(), p1.x(), p2.x()});
              const double lo_y = std::min({p0.y(), p1.y(), p2.y()});
              const double hi_y = std::max({p0.y(), p1.y(), p2.y()});
              const int x0 = std::max(0, int(std::ceil(lo_x - 0.5)));
              const int x1 = std::min(width - 1, int(std::floor(hi_x - 0.5)));
              const int y0 = std::max(0, int(std::ceil(lo_y - 0.5)));
              const int y1 = std::min(height - 1, int(std::floor(hi_y - 0.5)));
              for (int y = y0; y <= y1; ++y)
                for (int x = x0; x <= x1; ++x) {
                  const size_t pixel = size_t(y) * width + x;
                  if (r.owner[pixel] == m) continue;  // an earlier tile of this mesh has it
                  const Eigen::Vector2d q(x + 0.5, y + 0.5);
                  const double w0 = cross(p1 - q, p2 - q) / area;
                  const double w1 = cross(p2 - q, p0 - q) / area;
                  const double w2 = 1 - w0 - w1;
                  if (w0 < -1e-9 || w1 < -1e-9 || w2 < -1e-9) continue;
                  const Eigen::Vector2d start =
                      w0 * uv(c0[0], c0[1]) + w1 * uv(c1[0], c1[1]) + w2 * uv(c2[0], c2[1]);
                  const Eigen::Vector2d w = cover(q, start);
                  const Eigen::Vector3d colour = mesh_color(g, i, j, w.x(), w.y());
                  r.owner[pixel] = m;
                  for (int ch = 0; ch < 3; ++ch) r.planes[ch * n + pixel] = float(colour[ch]);
                }
            }
          }
      }
  }
  return r;
}

}  // namespace wisp::diffusion
