// The scalp: its coverage field is about 1 amid the roots, 1/2 at the edge of the area they cover
// and 0 away from it, whatever their density; seen through a camera it is the head's own surface
// (depth of the first hit, hidden by the head itself), and eye rays against triangles agree with
// the analytic sphere.
#include <catch2/catch.hpp>

#include <cmath>

#include "sim/body.hpp"
#include "sim/hair_model.hpp"
#include "sim/ray_triangle.hpp"
#include "sim/scalp.hpp"

using namespace wisp::sim;
using Eigen::Vector2d;
using Eigen::Vector3d;

namespace {

// The head alone (no neck or torso) as a triangle mesh of `slices` x `stacks`, and a square
// camera of `side` pixels looking at it from the default eye.
BodyModel head_model(const HeadGeometry& head, int slices, int stacks) {
  BodyParams b = body_params(HeadParams{});
  b.neck = b.torso = false;
  b.slices = slices;
  b.stacks = stacks;
  return BodyModel(head, b);
}

// Eye rays against the posed head of `model`.
std::shared_ptr<const SurfaceRays> head_rays(const BodyModel& model, const HeadPose& pose,
                                             const Camera& camera, bool with_folds = false) {
  BodySurface s = model.head_surface(pose);
  return std::make_shared<const SurfaceRays>(std::move(s.vertices), std::move(s.triangles), camera,
                                             with_folds);
}

Camera square_camera(int side) {
  CameraParams cp;
  cp.width = cp.height = side;
  return Camera::look_at(cp);
}

// Roots spread evenly (a Fibonacci spiral) over the cap of a sphere of radius `r` within
// `cap_deg` of +y.
std::vector<Vector3d> cap_roots(int count, double r, double cap_deg) {
  std::vector<Vector3d> out;
  const double zmin = std::cos(cap_deg * M_PI / 180), golden = M_PI * (3 - std::sqrt(5.0));
  for (int i = 0; i < count; ++i) {
    const double y = 1 - (1 - zmin) * (i + 0.5) / count, s = std::sqrt(1 - y * y);
    out.push_back(r * Vector3d(s * std::cos(golden * i), y, s * std::sin(golden * i)));
  }
  return out;
}

// The point of the sphere of radius r at `deg` from +y, towards +z.
Vector3d at_angle(double r, double deg) {
  const double a = deg * M_PI / 180;
  return r * Vector3d(0, std::cos(a), std::sin(a));
}

}  // namespace

TEST_CASE("scalp coverage: 1 amid the roots, 1/2 at their edge, 0 beyond, at any density",
          "[sim][scalp]") {
  for (int count : {80, 320}) {
    INFO(count << " roots");
    const Scalp scalp(cap_roots(count, 0.1, 60), 1.0);
    // The edge of the area the roots cover lies half a spacing beyond the outermost ring.
    const double spacing_deg = scalp.sigma() / 0.1 * 180 / M_PI;
    CHECK(scalp.coverage(at_angle(0.1, 0)) == Approx(1).margin(0.2));
    CHECK(scalp.coverage(at_angle(0.1, 30)) == Approx(1).margin(0.2));
    CHECK(scalp.coverage(at_angle(0.1, 60)) == Approx(0.5).margin(0.15));
    CHECK(scalp.coverage(at_angle(0.1, 60 + 3 * spacing_deg)) < 0.02);
    CHECK(scalp.coverage(Vector3d(0, -0.1, 0)) == 0);  // the far side of the head
  }
  // The field is smooth between the roots: no dips towards 1/2 inside the cap.
  const Scalp scalp(cap_roots(150, 0.1, 60));
  double lowest = 1e9;
  for (double deg = 0; deg <= 45; deg += 0.5)
    for (double az = 0; az < 360; az += 7) {
      const double a = deg * M_PI / 180, b = az * M_PI / 180;
      lowest =
          std::min(lowest, scalp.coverage(0.1 * Vector3d(std::sin(a) * std::cos(b), std::cos(a),
                                                         std::sin(a) * std::sin(b))));
    }
  CHECK(lowest > 0.75);
  CHECK_THROWS_AS(Scalp({}), std::invalid_argument);
  CHECK_THROWS_AS(Scalp(cap_roots(10, 0.1, 60), 0.0), std::invalid_argument);
}

TEST_CASE("eye rays against triangles meet the head where the analytic ellipsoid is",
          "[sim][scalp]") {
  HeadGeometry head;
  const BodyModel model = head_model(head, 96, 48);
  const Camera camera = square_camera(200);
  const auto rays = head_rays(model, HeadPose{}, camera);
  int hits = 0;
  for (int y = 0; y < 200; y += 7)
    for (int x = 0; x < 200; x += 7) {
      const Vector2d p(x + 0.5, y + 0.5);
      const Vector3d d = rays->ray(p);
      // The ray through p projects back onto p.
      CHECK((camera.project(camera.eye + d) - p).norm() < 1e-9);
      // Ray and ellipsoid: |(e + t d) / r| = 1.
      const Vector3d e = camera.eye.cwiseQuotient(head.radii), q = d.cwiseQuotient(head.radii);
      const double a = q.squaredNorm(), b = 2 * e.dot(q), c = e.squaredNorm() - 1;
      const double disc = b * b - 4 * a * c;
      const double depth = rays->depth(p);
      if (disc < 0) {
        CHECK(std::isinf(depth));
        continue;
      }
      const double t = (-b - std::sqrt(disc)) / (2 * a);
      // The tessellation contains the ellipsoid: a ray that meets one meets the other.
      if (std::isinf(depth)) FAIL("a ray that meets the ellipsoid misses its tessellation");
      ++hits;
      // And meets it first, within the facets' sagitta (about 1 mm).
      CHECK(depth <= t + 1e-9);
      CHECK(depth > t - 0.004);
    }
  CHECK(hits > 30);
  // A corner that is not a vertex is refused.
  CHECK_THROWS_AS(SurfaceRays({Vector3d::Zero()}, {Eigen::Vector3i(0, 1, 2)}, camera),
                  std::invalid_argument);
}

TEST_CASE("eye rays find the nearest of all triangles, on edges and corners too", "[sim][scalp]") {
  // The grid and each triangle's box and projected edges only skip triangles a ray cannot hit:
  // every answer is the one all triangles give, also where the ray passes next to a projected
  // corner or edge of the mesh (where a skip that is off by its margin would show).
  HeadGeometry head;
  const BodyModel model = head_model(head, 24, 12);
  const Camera camera = square_camera(160);
  HeadPose pose;
  pose.rotation = Eigen::AngleAxisd(0.4, Vector3d(0.3, 1, 0.2).normalized());
  const BodySurface s = model.head_surface(pose);
  const SurfaceRays rays(s.vertices, s.triangles, camera);
  const auto all_triangles = [&](const Vector2d& p) {
    double best = INFINITY;
    for (const Eigen::Vector3i& t : s.triangles) {
      const double h = ray_triangle(camera.eye, rays.ray(p), s.vertices[size_t(t[0])],
                                    s.vertices[size_t(t[1])], s.vertices[size_t(t[2])]);
      if (h > 0) best = std::min(best, h);
    }
    return best;
  };
  std::vector<Vector2d> points;
  for (const Eigen::Vector3i& t : s.triangles)
    for (int c = 0; c < 3; ++c) {
      const Vector2d a = rays.pixels()[size_t(t[c])], b = rays.pixels()[size_t(t[(c + 1) % 3])];
      // A millionth of a pixel around the corner and the edge's middle: through one triangle
      // or another, not through the corner or edge itself, where the 3D test's answer is
      // rounding's and two builds of it may differ.
      for (const Vector2d& o :
           {Vector2d(1e-6, 3e-7), Vector2d(-4e-7, 1e-6), Vector2d(-1e-6, -5e-7)})
        points.insert(points.end(), {a + o, 0.5 * (a + b) + o});
    }
  for (int y = 0; y < 160; y += 3)
    for (int x = 0; x < 160; x += 3) points.emplace_back(x + 0.37, y + 0.61);
  int hits = 0;
  for (const Vector2d& p : points) {
    const double expected = all_triangles(p);
    hits += std::isfinite(expected);
    INFO("pixel " << p.transpose());
    // The same triangle, up to how each build of the inline 3D test rounds.
    const double depth = rays.depth(p);
    if (std::isinf(expected))
      CHECK(std::isinf(depth));
    else
      CHECK(depth == Approx(expected).epsilon(1e-12));
  }
  CHECK(hits > 1000);
}

TEST_CASE("the scalp seen through a camera: crown inside, face outside, hidden by the head",
          "[sim][scalp]") {
  HeadGeometry head;
  HairParams hair;  // roots within 105 degrees of the crown, 62 degrees or more from the face
  const HeadShape shape(head);
  std::vector<Vector3d> roots;
  for (const Polyline& s : generate_hair(hair, shape)) roots.push_back(s.front());
  auto scalp = std::make_shared<const Scalp>(roots);
  BodyParams b = body_params(HeadParams{});
  b.neck = b.torso = false;
  const BodyModel model(head, b);
  CameraParams cp;
  cp.eye = Vector3d(0, 0.25, 1.0);  // in front, somewhat above
  cp.target = Vector3d(0, 0, 0);
  cp.width = cp.height = 256;
  const Camera camera = Camera::look_at(cp);
  HeadPose pose;
  pose.rotation = Eigen::AngleAxisd(0.3, Vector3d::UnitY());
  const ScalpView view(scalp, pose, head_rays(model, pose, camera));
  // The crown and the face, as the camera sees them.
  const Vector2d crown = camera.project(pose.to_world(shape.surface_point(Vector3d(0, 1, 0.3))));
  const Vector2d face = camera.project(pose.to_world(shape.surface_point(Vector3d(0, -0.2, 1))));
  CHECK(view.field(crown) > 0.3);
  CHECK(view.field(face) == Approx(-0.5).margin(0.01));
  CHECK(view.field(Vector2d(2, 2)) == -0.5);  // off the head
  // The depth is the distance to the head point seen there, on the near side.
  const Vector3d top = pose.to_world(shape.surface_point(Vector3d(0, 1, 0.3)));
  CHECK(view.depth(crown) == Approx((top - camera.eye).norm()).margin(0.003));
  // The back of the head is all scalp, but hidden: the ray through its projection meets the
  // face side first, bare skin.
  const Vector3d back = pose.to_world(shape.surface_point(Vector3d(0, 0.2, -1)));
  CHECK(scalp->coverage(pose.to_local(back)) > 0.5);
  CHECK(view.field(camera.project(back)) < 0);
}

TEST_CASE("the depth bound over a box holds at every point of it, and is near where it is known",
          "[sim][scalp]") {
  HeadGeometry head;
  const BodyModel model = head_model(head, 48, 24);
  const Camera camera = square_camera(200);
  const auto plain = head_rays(model, HeadPose{}, camera);
  const auto rays = head_rays(model, HeadPose{}, camera, true);
  CHECK(std::isinf(plain->max_depth(Eigen::AlignedBox2d(Vector2d(98, 98), Vector2d(102, 102)))));
  int known = 0, tight = 0;
  for (int y = 0; y < 200; y += 4)
    for (int x = 0; x < 200; x += 4) {
      const Eigen::AlignedBox2d box(Vector2d(x, y), Vector2d(x + 4, y + 4));
      const double bound = rays->max_depth(box);
      double deepest = 0;
      for (int k = 0; k <= 8; ++k)
        for (int l = 0; l <= 8; ++l)
          deepest = std::max(deepest, rays->depth(Vector2d(x + 0.5 * k, y + 0.5 * l)));
      if (std::isinf(bound)) continue;  // no bound: the box may reach past the silhouette
      ++known;
      CHECK(deepest <= bound);
      tight += bound < deepest + 0.01;  // the facets near the box, not the far side of the head
    }
  CHECK(known > 50);
  CHECK(tight > 0.9 * known);  // looser only where facets turn edge-on, at the silhouette
}
