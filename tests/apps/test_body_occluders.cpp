// The body's occluders (apps/render/body_occluders.hpp) on a turning head with a body
// (data/scenes/default.json): each silhouette ring is the convex hull of its surface's projected
// vertices, corners taken from them, every vertex inside or on it.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "apps/render/scene_frames.hpp"
#include "scene_fixture.hpp"

namespace render = wisp::render;
using Eigen::Vector2d;

namespace {

double cross(const Vector2d& o, const Vector2d& a, const Vector2d& b) {
  return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
}

}  // namespace

TEST_CASE("each occluder's ring is the convex hull of its surface's projected vertices",
          "[render][occluders]") {
  const render::SceneFrames& sf =
      wisp::test::loaded_scene(WISP_SOURCE_DIR "/data/scenes/default.json", 320);
  REQUIRE(sf.body);
  const wisp::sim::Camera camera = wisp::sim::Camera::look_at(sf.scene.camera);
  for (int k : wisp::test::five_angles(sf.anim)) {
    const wisp::sim::HeadPose& pose = sf.anim.frames.at(k).head;
    const std::vector<wisp::vector::Occluder> occluders = render::frame_occluders(sf, k);
    // The surfaces the occluders come from, in order (none of this scene's reaches behind the
    // eye, so none is left out).
    const std::vector<wisp::sim::BodySurface> surfaces = sf.body->surfaces(pose, camera.eye);
    REQUIRE(occluders.size() == surfaces.size());
    for (size_t o = 0; o < occluders.size(); ++o) {
      const std::vector<Vector2d>& ring = occluders[o].ring;
      REQUIRE(ring.size() >= 3);
      std::vector<Vector2d> pixels;
      Eigen::AlignedBox2d box;
      for (const Eigen::Vector3i& t : surfaces[o].triangles)
        for (int c = 0; c < 3; ++c) {
          pixels.push_back(camera.project(surfaces[o].vertices[size_t(t[c])]));
          box.extend(pixels.back());
        }
      const double tiny = 1e-12 * box.sizes().squaredNorm();
      const size_t n = ring.size();
      int outside = 0, convex = 0, corners = 0;
      for (size_t i = 0; i < n; ++i) {
        // Counter-clockwise, strictly convex at every corner.
        convex += cross(ring[i], ring[(i + 1) % n], ring[(i + 2) % n]) > 0;
        corners += std::find(pixels.begin(), pixels.end(), ring[i]) != pixels.end();
      }
      for (const Vector2d& p : pixels)
        for (size_t i = 0; i < n; ++i)
          if (cross(ring[i], ring[(i + 1) % n], p) < -tiny) {
            ++outside;
            break;
          }
      CHECK(convex == int(n));
      CHECK(corners == int(n));
      CHECK(outside == 0);
    }
  }
}
