// The body: sweeps (profiles, distances, meshes), the projected head against the analytic
// ellipse, roots inside the drawn head, the painter's order of whole surfaces against a ray-cast
// depth buffer, shading, the torso's share of the head's turn, occlusion of strands by the body,
// collision, and the pre-roll.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>

#include "sim/body.hpp"
#include "sim/camera.hpp"
#include "sim/hair_model.hpp"
#include "sim/motion.hpp"
#include "sim/sweep.hpp"
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
  BodyParams b = body_params(HeadParams{});
  b.neck = b.torso = false;
  return b;
}

double cross2(const Vector2d& a, const Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

double area(const ProjectedSurface& s, const Eigen::Vector3i& t) {
  return 0.5 * cross2(s.pixel[t[1]] - s.pixel[t[0]], s.pixel[t[2]] - s.pixel[t[0]]);
}

// Barycentric coordinates of q in triangle t, or nothing when q is outside.
bool barycentric(const ProjectedSurface& s, const Eigen::Vector3i& t, const Vector2d& q,
                 Vector3d* w = nullptr) {
  const Vector2d a = s.pixel[t[0]], b = s.pixel[t[1]], c = s.pixel[t[2]];
  const double d = cross2(b - a, c - a);
  if (d == 0) return false;
  const double w1 = cross2(q - a, c - a) / d, w2 = cross2(b - a, q - a) / d, w0 = 1 - w1 - w2;
  if (w0 < 0 || w1 < 0 || w2 < 0) return false;
  if (w) *w = Vector3d(w0, w1, w2);
  return true;
}

const ProjectedSurface& surface_of(const ProjectedBody& body, int part) {
  for (const ProjectedSurface& s : body.surfaces)
    if (s.part == part) return s;
  throw std::runtime_error("no such surface");
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

// Distance along the ray from `eye` in direction `dir` to triangle t of `s` (Moller-Trumbore),
// or a huge value when the ray misses it.
double ray_hit(const BodySurface& s, const Eigen::Vector3i& t, const Vector3d& eye,
               const Vector3d& dir) {
  constexpr double kMiss = 1e9;
  const Vector3d a = s.vertices[t[0]], e1 = s.vertices[t[1]] - a, e2 = s.vertices[t[2]] - a;
  const Vector3d p = dir.cross(e2);
  const double det = e1.dot(p);
  if (std::abs(det) < 1e-15) return kMiss;
  const Vector3d o = eye - a;
  const double u = o.dot(p) / det;
  if (u < 0 || u > 1) return kMiss;
  const Vector3d q = o.cross(e1);
  const double v = dir.dot(q) / det;
  if (v < 0 || u + v > 1) return kMiss;
  const double h = e2.dot(q) / det;
  return h > 0 ? h : kMiss;
}

}  // namespace

TEST_CASE("a sweep's profile is monotone between samples and its ends are round caps",
          "[sim][body]") {
  Sweep s;
  s.t = {0, 0.2, 0.5, 1};
  s.half_width = {0, 0.05, 0.08, 0};
  s.half_depth = {0, 0.04, 0.06, 0};
  s.offset = {0, 0.01, 0.01, 0};
  const SweepShape shape(s);
  double lo = 1, hi = 0;
  for (int i = 0; i <= 300; ++i) {
    const double t = 0.2 + 0.3 * i / 300;
    const SweepShape::Section sec = shape.section(t);
    lo = std::min(lo, sec.a);
    hi = std::max(hi, sec.a);
    CHECK(sec.z == Approx(0.01));  // a constant offset stays constant
  }
  CHECK(lo >= 0.05 - 1e-12);  // no overshoot between samples
  CHECK(hi <= 0.08 + 1e-12);
  // Near each end a ~ sqrt(distance to the end): a round cap, not a cone's point.
  const double a1 = shape.section(1e-4).a, a2 = shape.section(4e-4).a;
  CHECK(a2 / a1 == Approx(2).epsilon(0.05));
  CHECK_THROWS_WITH(validate_sweep(Sweep{{0, 1}, {0, 0}, {0, 0}, {0, 0}}, "neck_shape"),
                    Catch::StartsWith("neck_shape: "));
  s.half_width[1] = 0;
  CHECK_THROWS_WITH(validate_sweep(s, "arm_shape"), Catch::Contains("positive between"));
}

TEST_CASE("a sweep's mesh lies on its surface, turns outwards, and its normals are gradients",
          "[sim][body]") {
  const BodyParams b = body_params(HeadParams{});
  for (const Sweep* profile : {&b.torso_shape, &b.arm_shape, &b.neck_shape}) {
    const SweepShape shape(*profile);
    const double length = 0.4;
    const SweepMesh m = sweep_mesh(shape, length, 48, 0.01);
    double worst_on = 0, worst_normal = 0, volume = 0;
    std::vector<Vector3d> p;
    for (std::size_t i = 0; i < m.t.size(); ++i) {
      p.push_back(shape.point(m.t[i], m.theta[i], length));
      worst_on = std::max(worst_on, std::abs(shape.distance(p.back(), length)));
      if (m.t[i] <= 0 || m.t[i] >= 1) continue;
      // The normal against the distance's central-difference gradient.
      Vector3d grad;
      for (int k = 0; k < 3; ++k) {
        const Vector3d e = Vector3d::Unit(k) * 1e-6;
        grad[k] = shape.distance(p.back() + e, length) - shape.distance(p.back() - e, length);
      }
      worst_normal = std::max(
          worst_normal, (grad.normalized() - shape.normal(m.t[i], m.theta[i], length)).norm());
    }
    for (const Eigen::Vector3i& t : m.triangles) volume += p[t[0]].dot(p[t[1]].cross(p[t[2]])) / 6;
    INFO("sweep with " << profile->t.size() << " samples");
    CHECK(worst_on < 1e-9);
    CHECK(worst_normal < 1e-4);
    CHECK(volume > 0);  // outward triangles enclose a positive volume
  }
}

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
  REQUIRE(body.surfaces.size() == 1);
  const ProjectedSurface& s = body.surfaces[0];
  double sum = 0;
  for (const Eigen::Vector3i& t : s.triangles) sum += std::abs(area(s, t));
  const double expected = analytic_area(cam, pose, head.radii);
  std::printf(
      "[measured] ellipsoid silhouette: %.1f px^2 from %zu triangles, analytic %.1f px^2 "
      "(%.3f %%)\n",
      sum, s.triangles.size(), expected, 100 * (sum / expected - 1));
  // The front faces of a convex polyhedron tile its outline exactly once.
  CHECK(sum == Approx(expected).epsilon(0.002));
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
    const ProjectedSurface& head = surface_of(body, kBodyHead);
    int outside = 0;
    for (const ProjectedStrand& s : pf.strands) {
      bool in = false;
      for (const Eigen::Vector3i& t : head.triangles) in = in || barycentric(head, t, s.pixel[0]);
      outside += !in;
    }
    INFO("yaw/pitch/roll " << ypr.transpose());
    CHECK(outside == 0);
  }
}

TEST_CASE(
    "body surfaces are front faces, and painting them whole, back to front, cut where they run "
    "inside earlier solids, matches a depth buffer",
    "[sim][body]") {
  const BodyParams bp = body_params(HeadParams{});
  const CameraParams cp = three_quarter_camera(128);
  const Camera cam = Camera::look_at(cp);
  const BodyModel model(HeadGeometry{}, bp);
  for (const Vector3d& ypr : {Vector3d(40, 20, 0), Vector3d(-50, -10, 5)}) {
    INFO("yaw/pitch/roll " << ypr.transpose());
    HeadPose pose;
    pose.rotation = rotation_from_ypr(ypr);
    const ProjectedBody body = model.project(pose, cam, default_light_dir());
    const std::vector<BodySurface> world = model.surfaces(pose, cam.eye);
    REQUIRE(body.surfaces.size() == 5);  // two arms, torso, neck, head
    bool front = true;
    for (const ProjectedSurface& s : body.surfaces)
      for (const Eigen::Vector3i& t : s.triangles) front = front && area(s, t) < 0;
    CHECK(front);

    // Every pixel centre: the part the painter leaves on top (the last surface whose visible
    // part covers it) against the part of the nearest surface along the pixel's ray. Each
    // triangle visits only the pixels of its bounding box (one pixel wider for the world's
    // triangles, whose box is that of their projected corners).
    const int w = cp.width, h = cp.height;
    std::vector<int> painted(size_t(w) * h, -1), hit(size_t(w) * h, -1);
    std::vector<double> nearest(size_t(w) * h, 1e9);
    const auto for_pixels_in_box = [&](Eigen::AlignedBox2d box, int margin, const auto& visit) {
      const int x0 = std::max(0, int(std::floor(box.min().x())) - margin);
      const int y0 = std::max(0, int(std::floor(box.min().y())) - margin);
      const int x1 = std::min(w - 1, int(std::ceil(box.max().x())) + margin);
      const int y1 = std::min(h - 1, int(std::ceil(box.max().y())) + margin);
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) visit(x, y, size_t(y) * w + x);
    };
    for (const ProjectedSurface& s : body.surfaces)
      for (const Eigen::Vector3i& t : s.triangles) {
        Eigen::AlignedBox2d box;
        for (int k = 0; k < 3; ++k) box.extend(s.pixel[t[k]]);
        for_pixels_in_box(box, 0, [&](int x, int y, size_t i) {
          Vector3d b;
          if (!barycentric(s, t, Vector2d(x + 0.5, y + 0.5), &b)) return;
          const double clear =
              std::isinf(s.clearance[t[0]])
                  ? 1.0
                  : b[0] * s.clearance[t[0]] + b[1] * s.clearance[t[1]] + b[2] * s.clearance[t[2]];
          if (clear > 0) painted[i] = s.part;
        });
      }
    for (const BodySurface& s : world)
      for (const Eigen::Vector3i& t : s.triangles) {
        Eigen::AlignedBox2d box;
        bool in_front = true;
        for (int k = 0; k < 3; ++k) {
          box.extend(cam.project(s.vertices[t[k]]));
          in_front = in_front && cam.forward.dot(s.vertices[t[k]] - cam.eye) > 0;
        }
        if (!in_front) box = Eigen::AlignedBox2d(Vector2d(0, 0), Vector2d(w, h));
        for_pixels_in_box(box, 1, [&](int x, int y, size_t i) {
          const Vector2d q(x + 0.5, y + 0.5);
          const Vector3d dir = (cam.forward + (q.x() - 0.5 * w) / cam.focal_px * cam.right -
                                (q.y() - 0.5 * h) / cam.focal_px * cam.up)
                                   .normalized();
          const double d = ray_hit(s, t, cam.eye, dir);
          if (d < nearest[i]) {
            nearest[i] = d;
            hit[i] = s.part;
          }
        });
      }
    int covered = 0, agree = 0, coverage_mismatch = 0;
    for (size_t i = 0; i < painted.size(); ++i) {
      if ((painted[i] >= 0) != (hit[i] >= 0)) ++coverage_mismatch;
      if (painted[i] >= 0 && hit[i] >= 0) {
        ++covered;
        agree += painted[i] == hit[i];
      }
    }
    std::printf(
        "[measured] whole surfaces painted back to front versus ray-cast depth: %d of %d pixels "
        "agree (%.2f %%), %d pixels differ in coverage\n",
        agree, covered, 100.0 * agree / covered, coverage_mismatch);
    CHECK(covered > 2000);
    CHECK(agree >= 0.995 * covered);
    CHECK(coverage_mismatch <= 0.002 * cp.width * cp.height);
  }
}

TEST_CASE("shade is half-Lambert towards the light", "[sim][body]") {
  const CameraParams cp = three_quarter_camera(128);
  const Vector3d light = Vector3d(0.68, 0.04, 0.86).normalized();  // from the camera
  const auto shades = [&](const Vector3d& l) {
    const ProjectedSurface s =
        project_body(HeadPose{}, HeadGeometry{}, head_only(), cp, l).surfaces.at(0);
    std::vector<float> out;
    for (const Eigen::Vector3i& t : s.triangles)
      for (int k = 0; k < 3; ++k) out.push_back(s.shade[t[k]]);
    return out;
  };
  const std::vector<float> lit = shades(light);
  // Lit from the eye, every front vertex is at least grazing-lit, the middle faces the light.
  CHECK(*std::min_element(lit.begin(), lit.end()) >= 0.5f - 0.02f);
  CHECK(*std::max_element(lit.begin(), lit.end()) > 0.99f);
  for (float v : shades(-light)) CHECK(v <= 0.5f + 0.02f);
  for (float v : shades(Vector3d::Zero())) CHECK(v == Approx(0.5f));
}

TEST_CASE("the torso takes torso_turn of the head's yaw; nods and rolls stay on the neck",
          "[sim][body]") {
  const BodyShape shape(body_params(HeadParams{}));
  REQUIRE(shape.params().torso_turn == Approx(0.35));
  const auto torso_yaw = [&](const Vector3d& ypr) {
    HeadPose pose;
    pose.position = Vector3d(0.02, -0.01, 0.03);
    pose.rotation = rotation_from_ypr(ypr);
    const BodyShape::Placement p = shape.placement(pose, BodyShape::kTorso);
    const Eigen::AngleAxisd turn(0.35 * ypr[0] * M_PI / 180, Vector3d::UnitY());
    CHECK(p.frame.translation().isApprox(pose.position + turn * shape.params().torso_bottom));
    const Vector3d forward = p.frame.linear().col(2);
    CHECK(std::abs(forward.y()) < 1e-12);  // upright
    return std::atan2(forward.x(), forward.z()) * 180 / M_PI;
  };
  CHECK(torso_yaw(Vector3d(0, 0, 0)) == Approx(0).margin(1e-9));
  CHECK(torso_yaw(Vector3d(55, 0, 0)) == Approx(0.35 * 55));
  CHECK(torso_yaw(Vector3d(-30, 0, 0)) == Approx(-0.35 * 30));
  CHECK(torso_yaw(Vector3d(40, 25, -10)) == Approx(0.35 * 40));
  CHECK(torso_yaw(Vector3d(0, 30, 20)) == Approx(0).margin(1e-9));
  HeadPose turned;
  turned.rotation = rotation_from_ypr(Vector3d(40, 0, 0));
  CHECK(head_yaw(turned) == Approx(40 * M_PI / 180));

  // Behind the camera nothing is drawn.
  const BodyModel model(HeadGeometry{}, body_params(HeadParams{}));
  CameraParams inside = three_quarter_camera(64);
  inside.eye = Vector3d(0, 0, 0.2);  // just in front of the face, looking away from the body
  inside.target = Vector3d(0, 0, 1);
  const ProjectedBody none =
      model.project(HeadPose{}, Camera::look_at(inside), default_light_dir());
  for (const ProjectedSurface& s : none.surfaces) CHECK(s.triangles.empty());
}

TEST_CASE("bad body parameters are rejected naming the field", "[sim][body]") {
  BodyParams b = body_params(HeadParams{});
  b.neck_shape.half_width[2] = -1;
  CHECK_THROWS_WITH(BodyModel(HeadGeometry{}, b), Catch::Contains("body.neck_shape"));
  b = body_params(HeadParams{});
  b.slices = 2;
  CHECK_THROWS_WITH(BodyModel(HeadGeometry{}, b), Catch::Contains("body.slices"));
  b = body_params(HeadParams{});
  b.arm_bottom.y() = std::nan("");
  CHECK_THROWS_WITH(validate(b), "arm_bottom: not finite");  // the part is named by its users
  b = body_params(HeadParams{});
  b.torso_turn = 1.5;
  CHECK_THROWS_WITH(BodyShape(b), Catch::Contains("body.torso_turn"));
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
  const BodyShape body(*options.body);
  CHECK(body.blocks(HeadPose{}, cp.eye, Vector3d(0, -0.45, -0.2), 0, 0.004));
  CHECK(!body.blocks(HeadPose{}, cp.eye, Vector3d(0, -0.45, 0.15), 0, 0.004));
  // A sample 1 mm behind the chest's front surface (found by bisection along the eye ray):
  // hidden by the full chest, not by the chest shrunk by 4 mm (it lies in the hysteresis band).
  const Vector3d target(0, -0.45, 0);
  double lo = 0, hi = (target - cp.eye).norm();  // outside at lo, inside at hi
  const Vector3d dir = (target - cp.eye).normalized();
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    (body.distance(HeadPose{}, cp.eye + mid * dir) > 0 ? lo : hi) = mid;
  }
  const Vector3d skin = cp.eye + (lo + 0.001) * dir;
  CHECK(body.blocks(HeadPose{}, cp.eye, skin, 0, 0));
  CHECK(!body.blocks(HeadPose{}, cp.eye, skin, 0.004, 0));
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

TEST_CASE("body distance: zero on every drawn surface, signs and normals off it", "[sim][body]") {
  const BodyParams b = body_params(HeadParams{});
  const BodyShape shape(b);
  const BodyModel model(HeadGeometry{}, b);
  HeadPose pose;
  pose.position = Vector3d(0.02, -0.01, 0.03);
  pose.rotation = rotation_from_ypr(Vector3d(30, 10, 0));
  const BodyShape::Posed posed = shape.posed(pose);
  double worst = 0, worst_normal = 0, worst_off = 0;
  int checked = 0;
  for (const BodySurface& s : model.surfaces(pose, Vector3d(0, 0, 2))) {
    if (s.part == kBodyHead) continue;
    for (std::size_t v = 0; v < s.vertices.size(); v += 7) {
      const Vector3d& x = s.vertices[v];
      const Vector3d& nv = s.normals[v];
      Vector3d n;
      worst = std::max(worst, std::abs(shape.solid_distance(s.solid, posed, x, &n)));
      worst_normal = std::max(worst_normal, (n - nv).norm());
      // 2 mm out: first order, so within a fifth (at the caps the bound takes over).
      worst_off =
          std::max(worst_off,
                   std::abs(shape.solid_distance(s.solid, posed, x + 0.002 * nv) - 0.002) / 0.002);
      CHECK(shape.distance(posed, x - 0.01 * nv) < 0);
      ++checked;
    }
  }
  std::printf(
      "[measured] body distance on %d surface points: at most %.2g m, normals within %.2g, 2 mm "
      "off the surface within %.0f %%\n",
      checked, worst, worst_normal, 100 * worst_off);
  CHECK(checked > 500);
  CHECK(worst < 1e-9);
  CHECK(worst_normal < 1e-6);
  CHECK(worst_off < 0.2);
  // Beside and above the arm's dome no phantom surface: around its top, the estimate is within
  // a third of the distance to the nearest vertex of its (fine) mesh.
  const BodyShape::Placement arm = posed.at[BodyShape::kArmPlus];
  const BodySurface* arm_surface = nullptr;
  const std::vector<BodySurface> surfaces = model.surfaces(pose, Vector3d(0, 0, 2));
  for (const BodySurface& s : surfaces)
    if (s.solid == BodyShape::kArmPlus) arm_surface = &s;
  REQUIRE(arm_surface);
  for (const Vector3d& local : {Vector3d(0.1, 1, 0), Vector3d(0.06, 0.97, 0.03),
                                Vector3d(0.0, 1.1, 0.0), Vector3d(-0.05, 1.05, -0.05)}) {
    const Vector3d x = arm.frame * Vector3d(local.x(), local.y() * arm.length, local.z());
    double nearest = 1e9;
    for (const Vector3d& v : arm_surface->vertices) nearest = std::min(nearest, (v - x).norm());
    const double d = shape.solid_distance(BodyShape::kArmPlus, posed, x);
    INFO("local " << local.transpose() << ": estimate " << d << ", mesh " << nearest);
    CHECK(d > 0.66 * nearest);
    CHECK(d < 1.02 * nearest);
  }
  // Far away: a lower bound, still positive and large.
  CHECK(shape.distance(pose, Vector3d(0, 0, 2)) > 1);
  BodyParams none = b;
  none.neck = none.torso = false;
  CHECK(std::isinf(BodyShape(none).distance(pose, Vector3d(0, -0.3, 0))));
}

TEST_CASE("with shoulders on, strands stay out of the neck, torso and arms as drawn",
          "[sim][body]") {
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
  const BodyShape body(*setup.body);
  const Animation anim = simulate(setup);
  double deepest = 1;
  int resting = 0;  // samples within 1 cm of the shoulders, torso or arms
  for (const StrandFrame& f : anim.frames)
    for (const Polyline& s : f.strands)
      for (std::size_t i = 1; i < s.size(); ++i) {
        const double d = body.distance(f.head, s[i]);
        deepest = std::min(deepest, d);
        resting += d < 0.01;
      }
  std::printf(
      "[measured] long hair under a shake: smallest distance to the body %.3g m, %d samples "
      "resting on it\n",
      deepest, resting);
  CHECK(deepest >= 0);
  CHECK(resting > 100);  // the hair does reach the shoulders
}

TEST_CASE("the face turns with the head: the eyes move the way it turns and hide facing away",
          "[sim][body]") {
  CameraParams cp = three_quarter_camera(512);
  cp.eye = Vector3d(0, 0, 1);  // in front of the face
  cp.target = Vector3d::Zero();
  const Camera cam = Camera::look_at(cp);
  const BodyModel model(HeadGeometry{}, body_params(HeadParams{}));
  // The centroid of the irises' samples in the image, and how many features show.
  const auto eyes = [&](double yaw, int* features = nullptr) {
    HeadPose pose;
    pose.rotation = rotation_from_ypr(Vector3d(yaw, 0, 0));
    Vector2d sum = Vector2d::Zero();
    int n = 0;
    const std::vector<FaceStroke> face = model.face(pose, cam);
    for (const FaceStroke& s : face)
      if (s.feature == Feature::Iris)
        for (const Vector2d& p : s.points) sum += p, ++n;
    if (features) *features = int(face.size());
    return n > 0 ? Vector2d(sum / n) : Vector2d(NAN, NAN);
  };
  int all = 0;
  const Vector2d front = eyes(0, &all);
  CHECK(all == 9);  // two brows, lids and irises, the nose, the mouth and the lower lip
  CHECK(front.x() == Approx(256).margin(0.5));  // symmetric
  CHECK(front.y() > 256 - 20);                  // about level with the head's centre
  // Yaw turns the face towards +x, which is the image's right for this camera.
  double last = front.x();
  for (double yaw : {10.0, 25.0, 40.0}) {
    const Vector2d e = eyes(yaw);
    INFO("yaw " << yaw);
    CHECK(e.x() > last + 5);
    CHECK(std::abs(e.y() - front.y()) < 5);
    last = e.x();
  }
  CHECK(eyes(-25).x() < front.x() - 5);
  int behind = -1;
  eyes(180, &behind);
  CHECK(behind == 0);  // facing away: nothing shows
  // Seen from the side, only the near eye shows.
  HeadPose side;
  side.rotation = rotation_from_ypr(Vector3d(90, 0, 0));
  int irises = 0;
  for (const FaceStroke& s : model.face(side, cam)) irises += s.feature == Feature::Iris;
  CHECK(irises == 1);
  // Hidden samples split a line into visible runs, the widths fade to nothing at the outline.
  const std::vector<FaceLine> lines = face_lines(HeadShape(HeadGeometry{}));
  const std::vector<FaceStroke> cut = project_face(lines, HeadPose{}, cam, [](const Vector3d& x) {
    return std::abs(x.x()) < 0.004;  // a thin occluder down the middle of the face
  });
  int mouth_runs = 0;
  for (const FaceStroke& s : cut) mouth_runs += s.feature == Feature::Mouth;
  CHECK(mouth_runs == 4);  // the mouth and the lower lip, each cut in two
}

TEST_CASE("each posed surface's edge neighbours, found once per mesh, are its own", "[sim][body]") {
  // Found from the rest mesh (the neck's at its rest length), they must be those found from the
  // posed vertices, or the occluders' depth bound would see folds where there are none.
  const BodyModel model(HeadGeometry{}, body_params(HeadParams{}));
  for (const Vector3d& ypr : {Vector3d(0, 0, 0), Vector3d(35, -20, 10), Vector3d(-50, 30, -15)}) {
    HeadPose pose;
    pose.position = Vector3d(0.01, -0.02, 0.015);
    pose.rotation = rotation_from_ypr(ypr);
    const std::vector<BodySurface> surfaces = model.surfaces(pose, Vector3d(0.3, 0.1, 1.2));
    REQUIRE(surfaces.size() >= 4);  // arms, torso, neck, head
    for (const BodySurface& s : surfaces) {
      REQUIRE(s.neighbours);
      CHECK(*s.neighbours == edge_neighbours(s.vertices, s.triangles));
    }
  }
}
