// HeadShape: see head.hpp. The mesh signed distance is sampled once on a grid of about 64 cells
// along the longest axis: exact point-triangle distances in a narrow band around the surface, a
// chamfer sweep beyond it (only the band matters for collisions), and the sign from ray parity
// along x, which is why the mesh must be closed.
#include "sim/head.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

#include "sim/ray_triangle.hpp"

namespace wisp::sim {
namespace {

using Eigen::Vector3d;

// Closest point on triangle abc to p (Ericson, Real-Time Collision Detection, 5.1.5).
Vector3d closest_on_triangle(const Vector3d& p, const Vector3d& a, const Vector3d& b,
                             const Vector3d& c) {
  const Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
  const Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

}  // namespace

HeadShape::HeadShape(HeadGeometry geometry) : geometry_(std::move(geometry)) {
  if (geometry_.shape == HeadKind::Ellipsoid) {
    const Vector3d& r = geometry_.radii;
    if (!(r.minCoeff() > 0) || !r.allFinite())
      throw std::invalid_argument("head.radii: every radius must be a positive number");
    center_ = Vector3d::Zero();
    half_extent_ = r;
  } else {
    mesh_ = true;
    const TriangleMesh& m = geometry_.mesh;
    if (m.vertices.empty() || m.triangles.empty())
      throw std::invalid_argument("head.mesh: the mesh has no triangles");
    for (const auto& t : m.triangles)
      for (int k = 0; k < 3; ++k)
        if (t[k] < 0 || t[k] >= static_cast<int>(m.vertices.size()))
          throw std::invalid_argument("head.mesh: a triangle refers to a missing vertex");
    // Closed: every edge is shared by exactly two triangles (the sign test needs it).
    std::map<std::pair<int, int>, int> edges;
    for (const auto& t : m.triangles)
      for (int k = 0; k < 3; ++k) {
        const int a = t[k], b = t[(k + 1) % 3];
        ++edges[{std::min(a, b), std::max(a, b)}];
      }
    int open = 0;
    for (const auto& [e, uses] : edges) open += uses != 2;
    if (open > 0)
      throw std::invalid_argument("head.mesh: the mesh is not closed (" + std::to_string(open) +
                                  " edges are not shared by exactly two triangles)");
    Vector3d lo = m.vertices[0], hi = m.vertices[0];
    for (const auto& v : m.vertices) {
      lo = lo.cwiseMin(v);
      hi = hi.cwiseMax(v);
    }
    center_ = 0.5 * (lo + hi);
    half_extent_ = 0.5 * (hi - lo);
    build_mesh_grid();
  }
}

void HeadShape::build_mesh_grid() {
  const TriangleMesh& m = geometry_.mesh;
  constexpr int kCells = 64;
  const double pad = 0.25 * half_extent_.maxCoeff();
  cell_ = 2 * (half_extent_.maxCoeff() + pad) / kCells;
  origin_ = center_ - half_extent_ - Vector3d::Constant(pad);
  for (int a = 0; a < 3; ++a)
    n_[a] = static_cast<int>(std::ceil(2 * (half_extent_[a] + pad) / cell_)) + 1;
  const auto index = [&](int i, int j, int k) {
    return (static_cast<std::size_t>(k) * n_.y() + j) * n_.x() + i;
  };
  const double big = std::numeric_limits<float>::max();
  std::vector<double> dist(static_cast<std::size_t>(n_.x()) * n_.y() * n_.z(), big);

  // Exact unsigned distance in a band of 3 cells around each triangle.
  for (const auto& t : m.triangles) {
    const Vector3d& a = m.vertices[t[0]];
    const Vector3d& b = m.vertices[t[1]];
    const Vector3d& c = m.vertices[t[2]];
    const Vector3d lo = (a.cwiseMin(b).cwiseMin(c) - origin_) / cell_ - Vector3d::Constant(3);
    const Vector3d hi = (a.cwiseMax(b).cwiseMax(c) - origin_) / cell_ + Vector3d::Constant(3);
    for (int k = std::max(0, int(std::floor(lo.z())));
         k <= std::min(n_.z() - 1, int(std::ceil(hi.z()))); ++k)
      for (int j = std::max(0, int(std::floor(lo.y())));
           j <= std::min(n_.y() - 1, int(std::ceil(hi.y()))); ++j)
        for (int i = std::max(0, int(std::floor(lo.x())));
             i <= std::min(n_.x() - 1, int(std::ceil(hi.x()))); ++i) {
          const Vector3d p = origin_ + cell_ * Vector3d(i, j, k);
          double& d = dist[index(i, j, k)];
          d = std::min(d, (p - closest_on_triangle(p, a, b, c)).norm());
        }
  }
  // Chamfer sweeps (forward and backward, 26 neighbours) fill the rest with an upper bound.
  for (int pass = 0; pass < 2; ++pass) {
    const int s = pass == 0 ? 1 : -1;
    const int k0 = pass == 0 ? 0 : n_.z() - 1, j0 = pass == 0 ? 0 : n_.y() - 1,
              i0 = pass == 0 ? 0 : n_.x() - 1;
    for (int k = k0; k >= 0 && k < n_.z(); k += s)
      for (int j = j0; j >= 0 && j < n_.y(); j += s)
        for (int i = i0; i >= 0 && i < n_.x(); i += s) {
          double& d = dist[index(i, j, k)];
          for (int dk = -1; dk <= 1; ++dk)
            for (int dj = -1; dj <= 1; ++dj)
              for (int di = -1; di <= 1; ++di) {
                const int ii = i - s * di, jj = j - s * dj, kk = k - s * dk;
                if ((di | dj | dk) == 0 || ii < 0 || jj < 0 || kk < 0 || ii >= n_.x() ||
                    jj >= n_.y() || kk >= n_.z())
                  continue;
                d = std::min(d, dist[index(ii, jj, kk)] +
                                    cell_ * std::sqrt(double(di * di + dj * dj + dk * dk)));
              }
        }
  }
  // Sign by parity of crossings along +x, one ray per (j, k) row; the tiny offsets keep the rays
  // off mesh edges and vertices.
  sdf_.assign(dist.size(), 0.f);
  std::vector<double> hits;
  for (int k = 0; k < n_.z(); ++k)
    for (int j = 0; j < n_.y(); ++j) {
      const Vector3d o = origin_ + cell_ * Vector3d(-1, j + 1.3e-7, k + 2.9e-7);
      hits.clear();
      for (const auto& t : m.triangles) {
        const double h = ray_triangle(o, Vector3d::UnitX(), m.vertices[t[0]], m.vertices[t[1]],
                                      m.vertices[t[2]]);
        if (h > 0) hits.push_back(h);
      }
      std::sort(hits.begin(), hits.end());
      std::size_t crossed = 0;
      for (int i = 0; i < n_.x(); ++i) {
        const double x = cell_ * (i + 1);
        while (crossed < hits.size() && hits[crossed] < x) ++crossed;
        const double d = dist[index(i, j, k)];
        sdf_[index(i, j, k)] = static_cast<float>(crossed % 2 == 1 ? -d : d);
      }
    }
}

double HeadShape::grid_value(const Vector3d& p) const {
  const Vector3d g = (p - origin_) / cell_;
  double out = 0;
  // Outside the grid: distance to the grid box plus the border value (an upper bound, only far
  // from the head where nothing needs precision).
  const Vector3d clamped =
      g.cwiseMax(Vector3d::Zero()).cwiseMin((n_ - Eigen::Vector3i::Ones()).cast<double>());
  const double outside = (g - clamped).norm() * cell_;
  const int i = std::min(int(clamped.x()), n_.x() - 2), j = std::min(int(clamped.y()), n_.y() - 2),
            k = std::min(int(clamped.z()), n_.z() - 2);
  const double fx = clamped.x() - i, fy = clamped.y() - j, fz = clamped.z() - k;
  const auto at = [&](int a, int b, int c) {
    return double(sdf_[(static_cast<std::size_t>(k + c) * n_.y() + (j + b)) * n_.x() + (i + a)]);
  };
  out = (1 - fz) * ((1 - fy) * ((1 - fx) * at(0, 0, 0) + fx * at(1, 0, 0)) +
                    fy * ((1 - fx) * at(0, 1, 0) + fx * at(1, 1, 0))) +
        fz * ((1 - fy) * ((1 - fx) * at(0, 0, 1) + fx * at(1, 0, 1)) +
              fy * ((1 - fx) * at(0, 1, 1) + fx * at(1, 1, 1)));
  return out + outside;
}

double HeadShape::distance(const Vector3d& p, Vector3d* normal) const {
  if (!mesh_) {
    const Vector3d& r = geometry_.radii;
    const Vector3d q = p.cwiseQuotient(r);
    const Vector3d g = q.cwiseQuotient(r);  // half the gradient of |p/r|^2
    const double k0 = q.norm(), k1 = g.norm();
    if (normal) *normal = k1 > 1e-12 ? Vector3d(g / k1) : Vector3d::UnitY();
    if (k1 < 1e-12) return -r.minCoeff();
    return k0 * (k0 - 1) / k1;
  }
  const double d = grid_value(p);
  if (normal) {
    const double h = 0.5 * cell_;
    Vector3d grad;
    for (int a = 0; a < 3; ++a) {
      Vector3d e = Vector3d::Zero();
      e[a] = h;
      grad[a] = grid_value(p + e) - grid_value(p - e);
    }
    const double len = grad.norm();
    *normal = len > 1e-12 ? Vector3d(grad / len) : Vector3d::UnitY();
  }
  return d;
}

Vector3d HeadShape::surface_point(const Vector3d& direction) const {
  const Vector3d d = direction.normalized();
  if (!mesh_) return d / d.cwiseQuotient(geometry_.radii).norm();
  // Farthest crossing from the centre: the outer skin, even if the mesh folds (ears).
  double best = -1;
  for (const auto& t : geometry_.mesh.triangles) {
    const double h = ray_triangle(center_, d, geometry_.mesh.vertices[t[0]],
                                  geometry_.mesh.vertices[t[1]], geometry_.mesh.vertices[t[2]]);
    best = std::max(best, h);
  }
  if (best <= 0) return center_;
  return center_ + best * d;
}

}  // namespace wisp::sim
