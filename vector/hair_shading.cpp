// The tube lighting model (see hair_shading.hpp).
#include "vector/hair_shading.hpp"

#include <algorithm>
#include <cmath>

namespace wisp::vector {

using Eigen::Vector3d;

TubeFrame tube_frame(const Vector3d& T, const Vector3d& to_eye) {
  TubeFrame f;
  f.T = T;
  f.V = to_eye;
  Vector3d b = to_eye.cross(T);
  if (b.norm() < 1e-9) {
    // Looking along the strand: any direction across it will do.
    b = T.cross(std::abs(T.x()) < 0.9 ? Vector3d::UnitX() : Vector3d::UnitY());
  }
  f.B = b.normalized();
  Vector3d c = to_eye - to_eye.dot(T) * T;
  f.C = c.norm() > 1e-9 ? Vector3d(c.normalized()) : Vector3d(T.cross(f.B).normalized());
  return f;
}

Vector3d tube_normal(const TubeFrame& f, double u) {
  u = std::clamp(u, -1.0, 1.0);
  return u * f.B + std::sqrt(std::max(0.0, 1 - u * u)) * f.C;
}

double kajiya_kay_diffuse(const Vector3d& T, const Vector3d& L) {
  const double c = T.dot(L);
  return std::sqrt(std::max(0.0, 1 - c * c));
}

double kajiya_kay_specular(const Vector3d& T, const Vector3d& L, const Vector3d& V, double n) {
  const Vector3d h = L + V;
  if (h.norm() < 1e-12) return 0;
  const double c = T.dot(h.normalized());
  return std::pow(std::max(0.0, 1 - c * c), 0.5 * n);
}

double blinn(const Vector3d& N, const Vector3d& L, const Vector3d& V, double c) {
  const Vector3d h = L + V;
  if (h.norm() < 1e-12) return 0;
  return std::pow(std::max(0.0, N.dot(h.normalized())), c);
}

double depth_detail(double z, double z_near, double z_far) {
  if (!(z_far > z_near) || !(z_near > 0) || !(z > 0)) return 1;
  return std::clamp(1 - std::log(z / z_near) / std::log(z_far / z_near), 0.0, 1.0);
}

double back_light(const Vector3d& N, const Vector3d& V, double r) {
  return std::pow(std::abs(N.dot(V)), r);
}

double head_shadow(const Vector3d& head_normal, const Vector3d& L, const Lighting& m) {
  const double s = std::clamp(L.dot(head_normal) + m.head_offset, 0.0, 1.0);
  return 1 - m.head_shadow * (1 - s);
}

double intensity(const TubeFrame& f, double u, const Vector3d& L, const Lighting& m,
                 double shadow) {
  return m.ambient + shadow * (m.kajiya_diffuse * kajiya_kay_diffuse(f.T, L) +
                               m.lambert * std::max(0.0, tube_normal(f, u).dot(L)));
}

double max_intensity(const Lighting& m) {
  return m.ambient + m.kajiya_diffuse + m.lambert;
}

std::vector<double> lambert_iso_u(const TubeFrame& f, const Vector3d& L, double k) {
  const double a = f.B.dot(L), b = f.C.dot(L), R = std::hypot(a, b);
  if (R < 1e-12 || std::abs(k) > R) return {};
  const double phi = std::atan2(a, b), d = std::acos(std::clamp(k / R, -1.0, 1.0));
  std::vector<double> out;
  for (double theta : {phi - d, phi + d, phi - d + 2 * M_PI, phi + d - 2 * M_PI})
    if (theta >= -M_PI / 2 - 1e-12 && theta <= M_PI / 2 + 1e-12) {
      const double u = std::sin(std::clamp(theta, -M_PI / 2, M_PI / 2));
      if (out.empty() || std::abs(out.back() - u) > 1e-12) out.push_back(u);
    }
  std::sort(out.begin(), out.end());
  return out;
}

double lambert_peak_u(const TubeFrame& f, const Vector3d& L) {
  const double a = f.B.dot(L), b = f.C.dot(L), R = std::hypot(a, b);
  if (R < 1e-12) return 0;
  // u = sin(phi) = a / R for phi in [-pi/2, pi/2]; behind the tube (b < 0) the visible maximum is
  // at the outline nearest the light.
  return b >= 0 ? a / R : (a >= 0 ? 1.0 : -1.0);
}

}  // namespace wisp::vector
