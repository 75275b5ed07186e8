// Camera projection (pixels, depth, tangents) and head occlusion with hysteresis.
#include <catch2/catch.hpp>

#include <cmath>

#include "sim/camera.hpp"

using namespace wisp::sim;
using Eigen::Vector3d;

namespace {

CameraParams front_camera() {
  CameraParams c;
  c.eye = Vector3d(0, 0, 1);
  c.target = Vector3d::Zero();
  c.width = 400;
  c.height = 300;
  c.fov_deg = 60;
  return c;
}

StrandFrame one_point_frame(const Vector3d& p) {
  StrandFrame f;
  f.strands = {{p, p + Vector3d(0, -0.01, 0)}};
  return f;
}

}  // namespace

TEST_CASE("pinhole projection: pixels, depth and focal length", "[sim][camera]") {
  const Camera cam = Camera::look_at(front_camera());
  const double f = 150 / std::tan(M_PI / 6);
  CHECK(cam.focal_px == Approx(f));
  double depth = 0;
  const Eigen::Vector2d c = cam.project(Vector3d::Zero(), &depth);
  CHECK(c.x() == Approx(200));
  CHECK(c.y() == Approx(150));
  CHECK(depth == Approx(1));
  // Right and up in the world go right and up (smaller y) in the image.
  const Eigen::Vector2d p = cam.project(Vector3d(0.1, 0.05, 0), &depth);
  CHECK(p.x() == Approx(200 + f * 0.1));
  CHECK(p.y() == Approx(150 - f * 0.05));
  CHECK(depth == Approx(std::sqrt(1 + 0.01 + 0.0025)));
  CameraParams bad = front_camera();
  bad.up = Vector3d(0, 0, 1);
  CHECK_THROWS_WITH(Camera::look_at(bad), Catch::Contains("camera.up"));
}

TEST_CASE("projected frames carry tangents, depth and head occlusion", "[sim][camera]") {
  Projector proj(HeadGeometry{}, front_camera());
  StrandFrame f;
  // One strand from the face side straight back through the side of the head to behind it.
  f.strands = {{Vector3d(0.0, 0, 0.2), Vector3d(0.0, 0, 0.15), Vector3d(0.0, 0, -0.15),
                Vector3d(0.0, 0, -0.2)}};
  const ProjectedFrame out = proj.project(f);
  REQUIRE(out.strands.size() == 1);
  const ProjectedStrand& s = out.strands[0];
  CHECK(s.visible[0] == 1);
  CHECK(s.visible[1] == 1);
  CHECK(s.visible[2] == 0);
  CHECK(s.visible[3] == 0);
  CHECK(s.tangent[1].isApprox(Vector3d(0, 0, -1)));
  CHECK(s.depth[3] == Approx(1.2));
  CHECK(out.width == 400);
  CHECK(out.focal_px == Approx(150 / std::tan(M_PI / 6)));
  // A turned head: the pose is used (a sample 0.12 m to the head's local +z, turned 90 degrees
  // about y, ends up on the +x side of the head, visible from the front camera).
  StrandFrame turned = one_point_frame(Vector3d(0.12, 0, 0));
  turned.head.rotation = Eigen::AngleAxisd(M_PI / 2, Vector3d::UnitY());
  CHECK(proj.project(turned).strands[0].visible[0] == 1);
}

TEST_CASE("visibility does not flicker at the head's silhouette", "[sim][camera]") {
  // Find, behind the head, the x where the eye's ray grazes the head (fresh projectors have no
  // memory).
  double lo = 0, hi = 0.3;
  for (int it = 0; it < 40; ++it) {
    const double mid = 0.5 * (lo + hi);
    Projector fresh(HeadGeometry{}, front_camera());
    (fresh.project(one_point_frame(Vector3d(mid, 0, -0.15))).strands[0].visible[0] ? hi : lo) = mid;
  }
  const double edge = 0.5 * (lo + hi);
  const auto changes = [&](double hysteresis) {
    CameraParams cam = front_camera();
    cam.hysteresis = hysteresis;
    Projector proj(HeadGeometry{}, cam);
    int flips = 0, last = -1;
    for (int f = 0; f < 60; ++f) {
      const double jitter = 0.0008 * std::sin(1.7 * f);  // a strand trembling by +-0.8 mm
      const int v =
          proj.project(one_point_frame(Vector3d(edge + jitter, 0, -0.15))).strands[0].visible[0];
      flips += last >= 0 && v != last;
      last = v;
    }
    return flips;
  };
  const int without = changes(0.0), with = changes(0.004);
  std::printf(
      "[measured] silhouette visibility changes over 60 frames: %d without, %d with "
      "hysteresis\n",
      without, with);
  CHECK(without >= 10);
  CHECK(with <= 1);
}
