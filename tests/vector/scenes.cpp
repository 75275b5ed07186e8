// Test scenes: strands from parametric curves, and seeded random frames.
#include "tests/vector/scenes.hpp"

#include <cmath>
#include <random>

namespace wisp::test {

using Eigen::Vector2d;
using Eigen::Vector3d;

sim::ProjectedStrand strand_from(int id, int samples, const std::function<Vector3d(double)>& q) {
  sim::ProjectedStrand s;
  s.id = id;
  for (int i = 0; i < samples; ++i) {
    const double u = double(i) / (samples - 1);
    const Vector3d p = q(u);
    s.pixel.emplace_back(p.x(), p.y());
    s.depth.push_back(p.z());
    s.world.push_back(p);
    const double h = 1e-4;
    const Vector3d d = q(std::min(1.0, u + h)) - q(std::max(0.0, u - h));
    s.tangent.push_back(d.norm() > 0 ? Vector3d(d.normalized()) : Vector3d::UnitX());
    s.visible.push_back(1);
  }
  return s;
}

sim::ProjectedStrand straight(int id, Vector2d a, Vector2d b, double za, double zb, int samples) {
  return strand_from(id, samples, [=](double u) {
    const Vector2d p = a + u * (b - a);
    return Vector3d(p.x(), p.y(), za + u * (zb - za));
  });
}

sim::ProjectedFrame frame_of(std::vector<sim::ProjectedStrand> strands, int width, int height) {
  sim::ProjectedFrame f;
  f.width = width;
  f.height = height;
  f.focal_px = 800;
  f.strands = std::move(strands);
  return f;
}

sim::ProjectedFrame random_frame(int count, std::uint32_t seed, int width, int height, bool loops) {
  std::mt19937 rng(seed);
  auto uni = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  std::vector<sim::ProjectedStrand> strands;
  for (int i = 0; i < count; ++i) {
    const Vector2d root(uni(-20, width + 20), uni(-20, height + 20));
    const double angle = uni(0, 2 * M_PI);
    const Vector2d dir(std::cos(angle), std::sin(angle)), side(-dir.y(), dir.x());
    const double length = uni(60, 180);
    const double z0 = uni(2, 4), dz = uni(-0.3, 0.3);
    const double bend = uni(-0.3, 0.3);
    const Kind kind = Kind(i % 3);
    if (kind == Kind::Straight) {
      strands.push_back(strand_from(i, 10, [=](double u) {
        const Vector2d p = root + dir * length * u + side * bend * length * u * u;
        return Vector3d(p.x(), p.y(), z0 + dz * u);
      }));
    } else if (kind == Kind::Wavy) {
      // Wavelengths of 30-60 px with amplitudes of 3-10 px: radii of curvature down to 2 px, well
      // under the half-width, so the curvature clamp has work to do.
      const double amplitude = uni(3, 10), waves = length / uni(30, 60), phase = uni(0, 2 * M_PI);
      strands.push_back(strand_from(i, 8 + int(6 * waves), [=](double u) {
        const Vector2d p =
            root + dir * length * u +
            side * (amplitude * std::sin(2 * M_PI * waves * u + phase) + bend * length * u * u);
        return Vector3d(p.x(), p.y(), z0 + dz * u);
      }));
    } else {
      // A helix around the strand's axis seen from the side: radius r, `turns` turns; its depth
      // swings by the radius in scene units (front and back of each coil).
      const double r = uni(5, 12), pitch = uni(25, 45), turns = length / pitch;
      const double phase = uni(0, 2 * M_PI);
      // How much of the coil's depth axis shows on screen. The centre curve loops where the
      // coil moves backwards faster than the strand advances: tilt * r * 2 pi > pitch.
      const double tilt = loops ? uni(0.3, 0.9) : uni(0.1, 0.6) * pitch / (2 * M_PI * r);
      strands.push_back(strand_from(i, 8 + int(8 * turns), [=](double u) {
        const double a = 2 * M_PI * turns * u + phase;
        const Vector2d p =
            root + dir * (length * u + tilt * r * std::cos(a)) + side * r * std::sin(a);
        return Vector3d(p.x(), p.y(), z0 + dz * u + 0.01 * r * std::cos(a));
      }));
    }
  }
  return frame_of(std::move(strands), width, height);
}

}  // namespace wisp::test
