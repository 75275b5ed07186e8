// The head (ellipsoid and mesh signed distances) and keyframed head motion (C1 interpolation,
// presets, bad keyframes).
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <map>

#include "sim/head.hpp"
#include "sim/motion.hpp"

using namespace wisp::sim;
using Eigen::Vector3d;

namespace {

// A closed unit-ish sphere: a subdivided octahedron projected onto radius r.
TriangleMesh sphere_mesh(double r, int subdivisions) {
  TriangleMesh m;
  m.vertices = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  m.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                 {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (int s = 0; s < subdivisions; ++s) {
    std::vector<Eigen::Vector3i> next;
    std::map<std::pair<int, int>, int> mid;
    const auto midpoint = [&](int a, int b) {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      m.vertices.push_back((0.5 * (m.vertices[a] + m.vertices[b])).normalized());
      return mid[key] = static_cast<int>(m.vertices.size()) - 1;
    };
    for (const auto& t : m.triangles) {
      const int ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]), ca = midpoint(t[2], t[0]);
      next.push_back({t[0], ab, ca});
      next.push_back({ab, t[1], bc});
      next.push_back({ca, bc, t[2]});
      next.push_back({ab, bc, ca});
    }
    m.triangles = next;
  }
  for (auto& v : m.vertices) v = r * v.normalized();
  return m;
}

}  // namespace

TEST_CASE("ellipsoid signed distance: sign, surface and normal", "[sim][head]") {
  HeadGeometry g;
  g.radii = Vector3d(0.08, 0.1, 0.09);
  const HeadShape head(g);
  Vector3d n;
  CHECK(head.distance(Vector3d::Zero()) < 0);
  CHECK(head.distance(Vector3d(0, 0.1, 0), &n) == Approx(0).margin(1e-12));
  CHECK(n.isApprox(Vector3d::UnitY()));
  CHECK(head.distance(Vector3d(0.1, 0, 0)) == Approx(0.02).epsilon(1e-9));  // exact on an axis
  CHECK(head.distance(Vector3d(0, -0.09, 0)) == Approx(-0.01).epsilon(1e-9));
  const Vector3d p = head.surface_point(Vector3d(1, 1, 1));
  CHECK(head.distance(p) == Approx(0).margin(1e-12));
}

TEST_CASE("mesh signed distance matches the sphere it approximates", "[sim][head]") {
  HeadGeometry g;
  g.shape = HeadKind::Mesh;
  g.mesh = sphere_mesh(0.1, 4);  // 2048 triangles
  const HeadShape head(g);
  for (const Vector3d& dir :
       {Vector3d(1, 0.2, 0.1), Vector3d(-0.3, 1, 0.5), Vector3d(0.1, -0.4, -1)}) {
    const Vector3d u = dir.normalized();
    for (double r : {0.06, 0.095, 0.1, 0.104, 0.12}) {
      Vector3d n;
      const double d = head.distance(r * u, &n);
      INFO("r = " << r);
      CHECK(d == Approx(r - 0.1).margin(0.0015));  // tessellation + grid interpolation
      CHECK(n.dot(u) > 0.95);
    }
    CHECK(head.surface_point(u).norm() == Approx(0.1).margin(0.001));
  }
}

TEST_CASE("an open or empty head mesh is rejected", "[sim][head]") {
  HeadGeometry g;
  g.shape = HeadKind::Mesh;
  CHECK_THROWS_WITH(HeadShape(g), Catch::Contains("head.mesh"));
  g.mesh = sphere_mesh(0.1, 1);
  g.mesh.triangles.pop_back();
  CHECK_THROWS_WITH(HeadShape(g), Catch::Contains("not closed"));
  HeadGeometry e;
  e.radii = Vector3d(0.1, -0.1, 0.1);
  CHECK_THROWS_WITH(HeadShape(e), Catch::Contains("head.radii"));
}

TEST_CASE("head motion is C1: pose and velocity are continuous through keyframes",
          "[sim][motion]") {
  const HeadMotion m({Keyframe{0, {0, 0, 0}, {0, 0, 0}}, Keyframe{1, {0.1, 0, 0}, {30, 0, 0}},
                      Keyframe{1.5, {0, 0.05, 0}, {-20, 10, 5}},
                      Keyframe{3, {0, 0, 0}, {0, 0, 0}}});
  const double eps = 1e-6;
  for (double t : {1.0, 1.5}) {
    const HeadPose a = m.pose(t - eps), b = m.pose(t + eps);
    CHECK((a.position - b.position).norm() < 1e-6);
    CHECK(a.rotation.angularDistance(b.rotation) < 1e-6);
    // Velocity from the left equals velocity from the right.
    const double h = 1e-4;
    const Vector3d vl = (m.pose(t).position - m.pose(t - h).position) / h;
    const Vector3d vr = (m.pose(t + h).position - m.pose(t).position) / h;
    CHECK((vl - vr).norm() < 1e-2 * std::max(1.0, vl.norm()));
  }
  // Keys are interpolated exactly, and the motion starts from rest.
  CHECK(m.pose(1.0).position.isApprox(Vector3d(0.1, 0, 0)));
  CHECK(m.pose(1.0).rotation.isApprox(rotation_from_ypr(Vector3d(30, 0, 0))));
  CHECK((m.pose(1e-4).position - m.pose(0).position).norm() < 1e-6);
  CHECK(m.pose(10).position.isApprox(Vector3d::Zero()));
}

TEST_CASE("motion presets cover the duration and stay bounded", "[sim][motion]") {
  for (const MotionPreset preset :
       {MotionPreset::Turn, MotionPreset::Nod, MotionPreset::Shake, MotionPreset::Walk}) {
    MotionParams p;
    p.preset = preset;
    p.duration = 4;
    const HeadMotion m(p);
    INFO(choice_name(preset));
    CHECK(m.keys().back().time >= p.duration);
    double moved = 0;
    for (double t = 0; t <= 4; t += 0.01) {
      const HeadPose pose = m.pose(t);
      CHECK(pose.position.allFinite());
      CHECK(pose.position.norm() < 0.1);
      moved = std::max(moved, pose.rotation.angularDistance(Eigen::Quaterniond::Identity()) +
                                  pose.position.norm());
    }
    CHECK(moved > 0.01);
  }
}

TEST_CASE("NaN and unordered keyframes are rejected naming the key", "[sim][motion]") {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH(
      HeadMotion({Keyframe{0, {0, 0, 0}, {0, 0, 0}}, Keyframe{1, {nan, 0, 0}, {0, 0, 0}}}),
      Catch::Contains("motion.keys[1]"));
  CHECK_THROWS_WITH(
      HeadMotion({Keyframe{1, {0, 0, 0}, {0, 0, 0}}, Keyframe{1, {0, 0, 0}, {0, 0, 0}}}),
      Catch::Contains("motion.keys[1].time"));
  CHECK_THROWS_AS(HeadMotion(std::vector<Keyframe>{}), std::invalid_argument);
}
