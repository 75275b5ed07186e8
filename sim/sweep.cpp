// Sweeps: monotone profile splines, the distance estimate, surface points and meshes (see
// sweep.hpp).
#include "sim/sweep.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace wisp::sim {

using Eigen::Vector3d;

constexpr double kFar = 0.05;  // m: beyond this, distance() returns its cheap lower bound

void validate_sweep(const Sweep& s, const char* field) {
  const auto fail = [&](const std::string& what) {
    throw std::invalid_argument(std::string(field) + ": " + what);
  };
  const std::size_t n = s.t.size();
  if (n < 4) fail("needs at least 4 profile samples (two caps and a span between)");
  if (s.half_width.size() != n || s.half_depth.size() != n || s.offset.size() != n)
    fail("every profile list needs one value per sample");
  if (s.t.front() != 0 || s.t.back() != 1) fail("t must run from 0 to 1");
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(s.t[i]) || !std::isfinite(s.half_width[i]) ||
        !std::isfinite(s.half_depth[i]) || !std::isfinite(s.offset[i]))
      fail("not finite");
    if (i > 0 && !(s.t[i] > s.t[i - 1])) fail("t must increase");
    if (s.half_width[i] < 0 || s.half_depth[i] < 0) fail("half widths must be >= 0");
    const bool end = i == 0 || i + 1 == n;
    if (end != (s.half_width[i] == 0) || end != (s.half_depth[i] == 0))
      fail("half widths must be 0 at both ends and positive between");
  }
}

SweepShape::Spline SweepShape::monotone(const std::vector<double>& t,
                                        const std::vector<double>& v) {
  // Fritsch-Carlson slopes: weighted harmonic means of the neighbouring secants, zero at local
  // extrema; the end slopes from a three-point formula, limited the same way.
  const std::size_t n = t.size();
  Spline s{v, std::vector<double>(n, 0.0)};
  std::vector<double> h(n - 1), d(n - 1);
  for (std::size_t k = 0; k + 1 < n; ++k) {
    h[k] = t[k + 1] - t[k];
    d[k] = (v[k + 1] - v[k]) / h[k];
  }
  for (std::size_t k = 1; k + 1 < n; ++k) {
    if (d[k - 1] * d[k] <= 0) continue;
    const double w1 = 2 * h[k] + h[k - 1], w2 = h[k] + 2 * h[k - 1];
    s.m[k] = (w1 + w2) / (w1 / d[k - 1] + w2 / d[k]);
  }
  const auto end_slope = [](double h0, double h1, double d0, double d1) {
    double m = ((2 * h0 + h1) * d0 - h0 * d1) / (h0 + h1);
    if (m * d0 <= 0) return 0.0;
    if (d0 * d1 <= 0 && std::abs(m) > 3 * std::abs(d0)) m = 3 * d0;
    return m;
  };
  s.m[0] = end_slope(h[0], h[1], d[0], d[1]);
  s.m[n - 1] = end_slope(h[n - 2], h[n - 3], d[n - 2], d[n - 3]);  // n >= 4 (validated)
  return s;
}

SweepShape::SweepShape(const Sweep& sweep) : t_(sweep.t) {
  // The splines between the caps, flat where they meet them (a cap's rim is vertical).
  const std::size_t n = t_.size();
  a_ = monotone(t_, sweep.half_width);
  c_ = monotone(t_, sweep.half_depth);
  o_ = monotone(t_, sweep.offset);
  for (Spline* s : {&a_, &c_, &o_}) s->m[1] = s->m[n - 2] = 0;
  // The splines do not overshoot their samples, and the caps stay within their rims: every
  // section lies within its centre's offset plus its larger half-width of the axis.
  double r = 0, z = 0;
  for (std::size_t i = 0; i < n; ++i) {
    r = std::max({r, sweep.half_width[i], sweep.half_depth[i]});
    z = std::max(z, std::abs(sweep.offset[i]));
  }
  max_radius_ = z + r;
}

double SweepShape::lower_bound(const Vector3d& p, double length, Vector3d* normal) const {
  const double dy = p.y() < 0 ? -p.y() : p.y() > length ? p.y() - length : 0.0;
  // (std::hypot is exact and slow; this is a bound.)
  const double d = std::sqrt(p.x() * p.x() + p.z() * p.z() + dy * dy);
  if (normal) {
    const Vector3d v = p - Vector3d(0, std::clamp(p.y(), 0.0, length), 0);
    *normal = d > 1e-12 ? Vector3d(v / d) : Vector3d::UnitY();
  }
  return d - max_radius_;
}

void SweepShape::eval(const Spline& s, double t, double& value, double& slope) const {
  // Between the caps' rims only (t_[1] to t_[n-2]).
  const std::size_t k = std::clamp<std::size_t>(
      std::upper_bound(t_.begin(), t_.end(), t) - t_.begin(), 2, t_.size() - 2);
  const std::size_t i = k - 1;
  const double h = t_[i + 1] - t_[i], u = std::clamp((t - t_[i]) / h, 0.0, 1.0);
  const double u2 = u * u, u3 = u2 * u;
  value = (2 * u3 - 3 * u2 + 1) * s.v[i] + (u3 - 2 * u2 + u) * h * s.m[i] +
          (-2 * u3 + 3 * u2) * s.v[i + 1] + (u3 - u2) * h * s.m[i + 1];
  slope = ((6 * u2 - 6 * u) * s.v[i] + (3 * u2 - 4 * u + 1) * h * s.m[i] +
           (-6 * u2 + 6 * u) * s.v[i + 1] + (3 * u2 - 2 * u) * h * s.m[i + 1]) /
          h;
}

SweepShape::Section SweepShape::section(double t) const {
  Section s;
  const std::size_t n = t_.size();
  const bool bottom = t<t_[1], top = t> t_[n - 2];
  if (!bottom && !top) {
    eval(a_, t, s.a, s.da);
    eval(c_, t, s.c, s.dc);
    eval(o_, t, s.z, s.dz);
    return s;
  }
  // A cap: a quarter ellipse from the rim (u = 0) to the pole (u = 1); d/dt is infinite at the
  // pole, where callers do not ask.
  const std::size_t rim = bottom ? 1 : n - 2;
  const double span = bottom ? t_[1] : 1 - t_[n - 2];
  const double u = std::min(std::abs(t - t_[rim]) / span, 1.0), root = std::sqrt(1 - u * u);
  const double slope = root > 1e-12 ? (bottom ? 1 : -1) * u / (span * root) : 0.0;
  s.a = a_.v[rim] * root;
  s.c = c_.v[rim] * root;
  s.z = o_.v[rim];
  s.da = a_.v[rim] * slope;
  s.dc = c_.v[rim] * slope;
  return s;
}

SweepShape::Cap SweepShape::cap(bool top, double length) const {
  const std::size_t rim = top ? t_.size() - 2 : 1;
  Cap c;
  c.center = Vector3d(0, t_[rim] * length, o_.v[rim]);
  c.radii = Vector3d(a_.v[rim], (top ? 1 - t_[rim] : t_[rim]) * length, c_.v[rim]);
  return c;
}

double SweepShape::distance(const Vector3d& p, double length, Vector3d* normal) const {
  const double t = p.y() / length;
  Vector3d nb;
  const double bound = lower_bound(p, length, normal ? &nb : nullptr);
  // Far away the bound is enough. It is a true lower bound, so outside the larger of it and an
  // estimate is the better estimate.
  if (bound > kFar) {
    if (normal) *normal = nb;
    return bound;
  }
  const std::size_t n = t_.size();
  if (t <= t_[1] || t >= t_[n - 2]) {
    // In a cap's reach: the half ellipsoid's own first-order estimate, well-behaved up to its
    // pole (the sweep's estimate is not: there a' grows without bound).
    const Cap c = cap(t > 0.5, length);
    const Vector3d q = (p - c.center).cwiseQuotient(c.radii);
    const Vector3d q2 = q.cwiseQuotient(c.radii);
    const double k0 = q.norm(), k1 = q2.norm();
    if (k1 < 1e-12) {
      if (normal) *normal = Vector3d::UnitY();
      return -c.radii.minCoeff();
    }
    const double d = k0 * (k0 - 1) / k1;
    if (d > 0 && bound > d) {
      if (normal) *normal = nb;
      return bound;
    }
    if (normal) *normal = q2 / k1;
    return d;
  }
  const Section s = section(t);
  const double X = p.x() / s.a, Z = (p.z() - s.z) / s.c, F = std::sqrt(X * X + Z * Z);
  if (F < 1e-12) {  // on the axis: deep inside, any direction will do
    if (normal) *normal = Vector3d::UnitX();
    return -std::min(s.a, s.c);
  }
  const Vector3d grad(X / (s.a * F),
                      -(X * X * s.da / s.a + Z * (s.dz + Z * s.dc) / s.c) / (length * F),
                      Z / (s.c * F));
  const double g = grad.norm();
  const double d = (F - 1) / g;
  if (d > 0 && bound > d) {
    if (normal) *normal = nb;
    return bound;
  }
  if (normal) *normal = grad / g;
  return d;
}

Vector3d SweepShape::point(double t, double theta, double length) const {
  const Section s = section(t);
  return Vector3d(s.a * std::cos(theta), t * length, s.z + s.c * std::sin(theta));
}

Vector3d SweepShape::normal(double t, double theta, double length) const {
  if (t <= 0) return -Vector3d::UnitY();
  if (t >= 1) return Vector3d::UnitY();
  const Section s = section(t);
  if (s.a < 1e-12 || s.c < 1e-12) return Vector3d(0, t < 0.5 ? -1 : 1, 0);
  const double X = std::cos(theta), Z = std::sin(theta);
  return Vector3d(X / s.a, -(X * X * s.da / s.a + Z * (s.dz + Z * s.dc) / s.c) / length, Z / s.c)
      .normalized();
}

std::vector<double> SweepShape::ring_parameters(double spacing, double length) const {
  // Arc length of the outline (mean radius against height, and the centre's drift) on a fine
  // grid, then inverted at even steps.
  constexpr int kSamples = 4096;
  std::vector<double> arc(kSamples + 1, 0.0);
  Vector3d prev(0, 0, 0);
  for (int i = 0; i <= kSamples; ++i) {
    const double t = double(i) / kSamples;
    const Section s = section(t);
    const Vector3d q(0.5 * (s.a + s.c), t * length, s.z);
    if (i > 0) arc[i] = arc[i - 1] + (q - prev).norm();
    prev = q;
  }
  const int rings = std::clamp(int(std::ceil(arc.back() / spacing)), 2, 1024);
  std::vector<double> out(rings + 1);
  int j = 0;
  for (int k = 0; k <= rings; ++k) {
    const double target = arc.back() * k / rings;
    while (j + 1 < kSamples && arc[j + 1] < target) ++j;
    const double span = arc[j + 1] - arc[j];
    const double f = span > 0 ? std::clamp((target - arc[j]) / span, 0.0, 1.0) : 0.0;
    out[k] = (j + f) / kSamples;
  }
  out.front() = 0;
  out.back() = 1;
  return out;
}

SweepMesh sweep_mesh(const SweepShape& shape, double length, int slices, double spacing) {
  SweepMesh m;
  const std::vector<double> ts = shape.ring_parameters(spacing, length);
  const int rings = int(ts.size()) - 1;
  m.t.push_back(0);
  m.theta.push_back(0);
  for (int k = 1; k < rings; ++k)
    for (int j = 0; j < slices; ++j) {
      m.t.push_back(ts[k]);
      m.theta.push_back(2 * M_PI * j / slices);
    }
  m.t.push_back(1);
  m.theta.push_back(0);
  // Rings run from +x towards +z, and upwards along y: (up, around) is outward.
  m.triangles = pole_to_pole_triangles(slices, rings);
  return m;
}

std::vector<Eigen::Vector3i> pole_to_pole_triangles(int slices, int rings) {
  const int top = 1 + (rings - 1) * slices;
  const auto at = [&](int ring, int j) { return 1 + (ring - 1) * slices + j % slices; };
  std::vector<Eigen::Vector3i> out;
  for (int j = 0; j < slices; ++j) {
    out.emplace_back(0, at(1, j), at(1, j + 1));
    for (int k = 1; k + 1 < rings; ++k) {
      out.emplace_back(at(k, j), at(k + 1, j), at(k, j + 1));
      out.emplace_back(at(k + 1, j), at(k + 1, j + 1), at(k, j + 1));
    }
    out.emplace_back(top, at(rings - 1, j + 1), at(rings - 1, j));
  }
  return out;
}

}  // namespace wisp::sim
