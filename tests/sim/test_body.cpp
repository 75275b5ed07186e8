// Body projection: analytic silhouette area, roots inside the head, painter's order against a
// ray-cast depth buffer, culling, shading, occlusion of strands by the torso, and the pre-roll.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <map>

#include "sim/body.hpp"
#include "sim/camera.hpp"
#include "sim/hair_model.hpp"
#include "sim/motion.hpp"
#include "sim_fixtures.hpp"

using namespace wisp::sim;
using Eigen::Matrix3d;
using Eigen::Matrix4d;
using Eigen::Vector2d;
using Eigen::Vector3d;

namespace {

CameraParams three_quarter_camera(int size = 256) {
  CameraParams c;
  c.eye = Vector3d(0.68, 0.04, 0.86);
  c.target = Vector3d(0, -0.08, 0);
  c.fov_deg = 36;
  c.width = c.height = size;
  return c;
}

BodyParams head_only() {
  BodyParams b;
  b.neck = b.torso = false;
  return b;
}

double cross2(const Vector2d& a, const Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

double area(const BodyTriangle& t) {
  return 0.5 * cross2(t.p[1] - t.p[0], t.p[2] - t.p[0]);
}

bool contains(const BodyTriangle& t, const Vector2d& q) {
  const double a = cross2(t.p[1] - t.p[0], q - t.p[0]), b = cross2(t.p[2] - t.p[1], q - t.p[1]),
               c = cross2(t.p[0] - t.p[2], q - t.p[2]);
  return (a <= 0 && b <= 0 && c <= 0) || (a >= 0 && b >= 0 && c >= 0);
}

// The camera as a 3x4 matrix on homogeneous points: (u w, v w, w), pixels with y down.
Eigen::Matrix<double, 3, 4> camera_matrix(const Camera& c) {
  const double cx = 0.5 * c.width, cy = 0.5 * c.height, f = c.focal_px;
  Eigen::Matrix<double, 3, 4> P;
  const Vector3d r0 = f * c.right + cx * c.forward, r1 = -f * c.up + cy * c.forward;
  P.row(0) << r0.transpose(), -r0.dot(c.eye);
  P.row(1) << r1.transpose(), -r1.dot(c.eye);
  P.row(2) << c.forward.transpose(), -c.forward.dot(c.eye);
  return P;
}

// Area of the image of the ellipsoid {x : (x - p)^T M (x - p) = 1}, M = R diag(1/r^2) R^T: the
// outline is the conic dual to P Q* P^T.
double analytic_area(const Camera& cam, const HeadPose& pose, const Vector3d& radii) {
  const Matrix3d R = pose.rotation.toRotationMatrix();
  const Matrix3d M = R * radii.cwiseInverse().cwiseAbs2().asDiagonal() * R.transpose();
  Matrix4d Q = Matrix4d::Zero();
  Q.topLeftCorner<3, 3>() = M;
  Q.topRightCorner<3, 1>() = -M * pose.position;
  Q.bottomLeftCorner<1, 3>() = (-M * pose.position).transpose();
  Q(3, 3) = pose.position.dot(M * pose.position) - 1;
  const Eigen::Matrix<double, 3, 4> P = camera_matrix(cam);
  const Matrix3d dual = P * Q.inverse() * P.transpose();
  const Matrix3d C = dual.inverse();
  return M_PI * std::abs(C.determinant()) /
         std::pow(std::abs(C.topLeftCorner<2, 2>().determinant()), 1.5);
}

}  // namespace

TEST_CASE("a known ellipsoid projects to the analytic ellipse area", "[sim][body]") {
  HeadGeometry head;
  head.radii = Vector3d(0.078, 0.105, 0.095);
  const CameraParams cp = three_quarter_camera(512);
  const Camera cam = Camera::look_at(cp);
  // Off centre and turned, so the outline is a general ellipse.
  HeadPose pose;
  pose.position = Vector3d(0.05, 0.03, -0.04);
  pose.rotation = rotation_from_ypr(Vector3d(30, 15, -10));
  const ProjectedBody body = project_body(pose, head, head_only(), cp, default_light_dir());
  double sum = 0;
  for (const BodyTriangle& t : body.triangles) sum += std::abs(area(t));
  const double expected = analytic_area(cam, pose, head.radii);
  std::printf(
      "[measured] ellipsoid silhouette: %.1f px^2 from %zu triangles, analytic %.1f px^2 "
      "(%.2f %%)\n",
      sum, body.triangles.size(), expected, 100 * (sum / expected - 1));
  // The front faces of a convex polyhedron tile its outline exactly once.
  CHECK(sum == Approx(expected).epsilon(0.02));
  CHECK(sum >= expected);  // circumscribed: never smaller than the true head
}

TEST_CASE("the projected head contains every strand root, as the hair projection sees them",
          "[sim][body]") {
  HeadParams hp;
  HairParams hair;
  hair.count = 150;
  const HeadShape shape(HeadGeometry{});
  const std::vector<Polyline> rest = generate_hair(hair, shape);
  const CameraParams cp = three_quarter_camera(256);
  Projector projector(HeadGeometry{}, cp);
  const BodyModel model(HeadGeometry{}, body_params(hp));
  for (const Vector3d& ypr : {Vector3d(0, 0, 0), Vector3d(55, 0, 0), Vector3d(-40, 20, 5)}) {
    StrandFrame frame;
    frame.head.position = Vector3d(0.01, -0.02, 0.0);
    frame.head.rotation = rotation_from_ypr(ypr);
    for (const Polyline& s : rest) frame.strands.push_back({frame.head.to_world(s[0])});
    const ProjectedFrame pf = projector.project(frame);
    const ProjectedBody body = model.project(frame.head, projector.camera(), pf.light_dir);
    int outside = 0;
    for (const ProjectedStrand& s : pf.strands) {
      bool in = false;
      for (const BodyTriangle& t : body.triangles)
        in = in || (t.part == kBodyHead && contains(t, s.pixel[0]));
      outside += !in;
    }
    INFO("yaw/pitch/roll " << ypr.transpose());
    CHECK(outside == 0);
  }
}

TEST_CASE(
    "body triangles are front faces, back to front, and the painter's order matches a "
    "depth buffer",
    "[sim][body]") {
  const HeadParams hp;
  const BodyParams bp = body_params(hp);
  const CameraParams cp = three_quarter_camera(128);
  const Camera cam = Camera::look_at(cp);
  const BodyModel model(HeadGeometry{}, bp);
  HeadPose pose;
  pose.rotation = rotation_from_ypr(Vector3d(40, 20, 0));
  const ProjectedBody body = model.project(pose, cam, default_light_dir());
  REQUIRE(body.triangles.size() > 100);
  bool sorted = true, front = true, parts[3] = {false, false, false};
  for (std::size_t i = 0; i < body.triangles.size(); ++i) {
    const BodyTriangle& t = body.triangles[i];
    if (i > 0) sorted = sorted && body.triangles[i - 1].depth >= t.depth;
    front = front && area(t) < 0;
    parts[t.part] = true;
  }
  CHECK(sorted);
  CHECK(front);
  CHECK((parts[kBodyHead] && parts[kBodyNeck] && parts[kBodyTorso]));

  // Every pixel centre: the part the painter's algorithm leaves on top versus the part of the
  // nearest surface along the pixel's ray (all world triangles, no culling).
  std::vector<int> part;
  const std::vector<Matrix3d> world = model.world_triangles(pose, &part);
  int covered = 0, agree = 0, coverage_mismatch = 0;
  for (int y = 0; y < cp.height; ++y)
    for (int x = 0; x < cp.width; ++x) {
      const Vector2d q(x + 0.5, y + 0.5);
      int painted = -1;
      for (const BodyTriangle& t : body.triangles)
        if (contains(t, q)) painted = t.part;
      const Vector3d dir = (cam.forward + (q.x() - 0.5 * cp.width) / cam.focal_px * cam.right -
                            (q.y() - 0.5 * cp.height) / cam.focal_px * cam.up)
                               .normalized();
      double nearest = 1e9;
      int hit = -1;
      for (std::size_t i = 0; i < world.size(); ++i) {
        const Vector3d a = world[i].col(0), e1 = world[i].col(1) - a, e2 = world[i].col(2) - a;
        const Vector3d p = dir.cross(e2);
        const double det = e1.dot(p);
        if (std::abs(det) < 1e-15) continue;
        const Vector3d s = cam.eye - a;
        const double u = s.dot(p) / det;
        if (u < 0 || u > 1) continue;
        const Vector3d qq = s.cross(e1);
        const double v = dir.dot(qq) / det;
        if (v < 0 || u + v > 1) continue;
        const double t = e2.dot(qq) / det;
        if (t > 0 && t < nearest) {
          nearest = t;
          hit = part[i];
        }
      }
      if ((painted >= 0) != (hit >= 0)) ++coverage_mismatch;
      if (painted >= 0 && hit >= 0) {
        ++covered;
        agree += painted == hit;
      }
    }
  std::printf(
      "[measured] painter's order versus ray-cast depth: %d of %d pixels agree (%.2f %%), "
      "%d pixels differ in coverage\n",
      agree, covered, 100.0 * agree / covered, coverage_mismatch);
  CHECK(covered > 2000);
  CHECK(agree >= 0.995 * covered);
  CHECK(coverage_mismatch <= 0.002 * cp.width * cp.height);
}

TEST_CASE("shade is half-Lambert towards the light", "[sim][body]") {
  const CameraParams cp = three_quarter_camera(128);
  const Vector3d light = Vector3d(0.68, 0.04, 0.86).normalized();  // from the camera
  const ProjectedBody body = project_body(HeadPose{}, HeadGeometry{}, head_only(), cp, light);
  float lo = 1, hi = 0;
  for (const BodyTriangle& t : body.triangles) {
    lo = std::min(lo, t.shade);
    hi = std::max(hi, t.shade);
  }
  // Lit from the eye, every front face is at least grazing-lit, the middle faces the light.
  CHECK(lo >= 0.5f - 1e-4f);
  CHECK(hi > 0.99f);
  const ProjectedBody back = project_body(HeadPose{}, HeadGeometry{}, head_only(), cp, -light);
  for (const BodyTriangle& t : back.triangles) CHECK(t.shade <= 0.5f + 1e-4f);
  const ProjectedBody none =
      project_body(HeadPose{}, HeadGeometry{}, head_only(), cp, Vector3d::Zero());
  for (const BodyTriangle& t : none.triangles) CHECK(t.shade == Approx(0.5f));
}

TEST_CASE("vertex shades follow the smooth surface and agree between neighbours", "[sim][body]") {
  const CameraParams cp = three_quarter_camera(256);
  const Camera cam = Camera::look_at(cp);
  HeadGeometry head;
  const BodyModel model(head, head_only());
  const ProjectedBody body = model.project(HeadPose{}, cam, default_light_dir());
  // Every corner's vertex normal against the analytic ellipsoid normal there.
  std::vector<Eigen::Matrix3d> normals;
  const std::vector<Matrix3d> world = model.world_triangles(HeadPose{}, nullptr, &normals);
  double worst_analytic = 0, worst_neighbour = 0;
  for (std::size_t i = 0; i < world.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const Vector3d analytic = world[i].col(k).cwiseQuotient(head.radii.cwiseAbs2()).normalized();
      worst_analytic = std::max(worst_analytic, (normals[i].col(k) - analytic).norm());
    }
  // A vertex shared by several drawn triangles has one shade.
  std::map<std::pair<double, double>, float> seen;
  for (const BodyTriangle& t : body.triangles)
    for (int k = 0; k < 3; ++k) {
      const auto [it, fresh] =
          seen.emplace(std::make_pair(t.p[k].x(), t.p[k].y()), t.vertex_shade[k]);
      if (!fresh)
        worst_neighbour =
            std::max(worst_neighbour, double(std::abs(it->second - t.vertex_shade[k])));
    }
  std::printf("[measured] vertex normals: at most %.3f from the analytic ellipsoid normal\n",
              worst_analytic);
  CHECK(worst_analytic < 0.05);
  CHECK(worst_neighbour == 0);
}

TEST_CASE("the torso follows the head's position only; behind the camera nothing is drawn",
          "[sim][body]") {
  const BodyModel model(HeadGeometry{}, body_params(HeadParams{}));
  std::vector<int> part;
  HeadPose turned;
  turned.rotation = rotation_from_ypr(Vector3d(60, 20, 0));
  const auto still = model.world_triangles(HeadPose{}, &part);
  const auto moved = model.world_triangles(turned, nullptr);
  REQUIRE(still.size() == moved.size());
  bool torso_same = true, head_moved = false;
  for (std::size_t i = 0; i < still.size(); ++i) {
    if (part[i] == kBodyTorso) torso_same = torso_same && still[i] == moved[i];
    if (part[i] == kBodyHead) head_moved = head_moved || !still[i].isApprox(moved[i]);
  }
  CHECK(torso_same);
  CHECK(head_moved);

  CameraParams inside = three_quarter_camera(64);
  inside.eye = Vector3d(0, 0, 0.2);  // just in front of the face, looking away from the body
  inside.target = Vector3d(0, 0, 1);
  const ProjectedBody none =
      model.project(HeadPose{}, Camera::look_at(inside), default_light_dir());
  CHECK(none.triangles.empty());
}

TEST_CASE("bad body parameters are rejected naming the field", "[sim][body]") {
  BodyParams b;
  b.neck_radius = 0;
  CHECK_THROWS_WITH(BodyModel(HeadGeometry{}, b), Catch::Contains("body.neck_radius"));
  b = BodyParams{};
  b.slices = 2;
  CHECK_THROWS_WITH(BodyModel(HeadGeometry{}, b), Catch::Contains("body.slices"));
  b = BodyParams{};
  b.chest_radii.y() = std::nan("");
  CHECK_THROWS_WITH(validate(b), Catch::StartsWith("chest_radii: "));
}

TEST_CASE("the drawn neck and torso hide strands behind them; frames carry the light",
          "[sim][body]") {
  CameraParams cp = three_quarter_camera(256);
  cp.eye = Vector3d(0, -0.1, 1.1);
  cp.target = Vector3d(0, -0.1, 0);
  StrandFrame frame;
  // A strand hanging down the back, behind the chest, and one hanging in front of it.
  frame.strands = {{Vector3d(0, -0.2, -0.2), Vector3d(0, -0.35, -0.2)},
                   {Vector3d(0, -0.2, 0.15), Vector3d(0, -0.35, 0.15)}};
  ProjectorOptions options;
  options.light_dir = Vector3d(0, 2, 0);
  options.body = std::make_shared<const BodyParams>(body_params(HeadParams{}));
  Projector with_body(HeadGeometry{}, cp, options);
  Projector head_only_projector(HeadGeometry{}, cp);
  const ProjectedFrame a = with_body.project(frame), b = head_only_projector.project(frame);
  CHECK(a.light_dir.isApprox(Vector3d::UnitY()));
  CHECK(b.light_dir.isApprox(default_light_dir()));
  CHECK(a.strands[0].visible == std::vector<std::uint8_t>{0, 0});
  CHECK(a.strands[1].visible == std::vector<std::uint8_t>{1, 1});
  CHECK(b.strands[0].visible == std::vector<std::uint8_t>{1, 1});
  // Direct checks of the analytic test, with and without the hysteresis shrink.
  const BodyParams& body = *options.body;
  CHECK(body_blocks(body, HeadPose{}, cp.eye, Vector3d(0, -0.45, -0.2), 0, 0.004));
  CHECK(!body_blocks(body, HeadPose{}, cp.eye, Vector3d(0, -0.45, 0.15), 0, 0.004));
  // A sample 1 mm behind the chest's front surface: hidden by the full chest, not by the chest
  // shrunk by 4 mm (it lies in the hysteresis band).
  const double front = body.chest_center.z() + body.chest_radii.z();
  const Vector3d skin(0, body.chest_center.y(), front - 0.001);
  CHECK(body_blocks(body, HeadPose{}, cp.eye, skin, 0, 0));
  CHECK(!body_blocks(body, HeadPose{}, cp.eye, skin, 0.004, 0));
  options.light_dir = Vector3d::Zero();
  CHECK_THROWS_WITH(Projector(HeadGeometry{}, cp, options), Catch::Contains("light.direction"));
}

TEST_CASE("a pre-roll settles the hair before frame 0", "[sim][physics]") {
  SimSetup setup = test::small_head(8, 12, HairCurl::Wavy, MotionPreset::None, 1.0);
  const Animation plain = simulate(setup);
  setup.sim.preroll = 0.5;
  setup.duration = 0.5;
  const Animation rolled = simulate(setup);
  // A still head and no gusts: the physics does not depend on the clock, so frame 0 after a
  // 0.5 s pre-roll is frame 12 (0.5 s at 24 fps) of the plain run.
  REQUIRE(plain.frames.size() == 25);
  REQUIRE(rolled.frames.size() == 13);
  CHECK(rolled.frames[0].time == 0);
  double worst = 0;
  for (std::size_t s = 0; s < setup.rest.size(); ++s)
    for (std::size_t i = 0; i < setup.rest[s].size(); ++i)
      worst =
          std::max(worst, (rolled.frames[0].strands[s][i] - plain.frames[12].strands[s][i]).norm());
  CHECK(worst < 1e-9);
  setup.sim.preroll = -1;
  CHECK_THROWS_WITH(simulate(setup), Catch::Contains("sim.preroll"));
}

TEST_CASE("body distance: neck and chest surfaces, signs and normals", "[sim][body]") {
  const BodyParams b = body_params(HeadParams{});
  HeadPose pose;
  pose.position = Vector3d(0.02, -0.01, 0.03);
  Vector3d n;
  // On the chest's front surface at its centre height: distance 0, normal +z.
  const Vector3d front = pose.position + b.chest_center + Vector3d(0, 0, b.chest_radii.z());
  CHECK(std::abs(body_distance(b, pose, front, &n)) < 1e-9);
  CHECK(n.isApprox(Vector3d::UnitZ(), 1e-9));
  CHECK(body_distance(b, pose, front + Vector3d(0, 0, 0.01)) == Approx(0.01).epsilon(1e-6));
  CHECK(body_distance(b, pose, front - Vector3d(0, 0, 0.01)) < 0);
  // Around the neck's middle: radius off the axis.
  const Vector3d top = pose.to_world(b.neck_top), bottom = pose.position + b.neck_bottom;
  const Vector3d mid = 0.5 * (top + bottom);
  const Vector3d side = (bottom - top).cross(Vector3d::UnitZ()).normalized();
  CHECK(body_distance(b, pose, mid + (b.neck_radius + 0.02) * side, &n) == Approx(0.02));
  CHECK(n.isApprox(side, 1e-9));
  // Far away: a lower bound, still positive and large.
  CHECK(body_distance(b, pose, Vector3d(0, 0, 2)) > 1);
  BodyParams none = b;
  none.neck = none.torso = false;
  CHECK(std::isinf(body_distance(none, pose, mid)));
}

TEST_CASE("with shoulders on, strands stay out of the neck and chest as drawn", "[sim][body]") {
  HeadParams head;
  head.shoulders = true;
  HairParams hair;
  hair.count = 40;
  hair.segments = 16;
  hair.length = 0.45;
  MotionParams motion;
  motion.preset = MotionPreset::Shake;
  motion.duration = 1.5;
  const SimSetup setup = make_setup(head, hair, motion, SimParams{});
  REQUIRE(setup.body);
  const Animation anim = simulate(setup);
  double deepest = 1;
  for (const StrandFrame& f : anim.frames)
    for (const Polyline& s : f.strands)
      for (std::size_t i = 1; i < s.size(); ++i)
        deepest = std::min(deepest, body_distance(*setup.body, f.head, s[i]));
  std::printf(
      "[measured] long hair under a shake: smallest distance to the neck and chest %.3g m\n",
      deepest);
  CHECK(deepest >= 0);
}
