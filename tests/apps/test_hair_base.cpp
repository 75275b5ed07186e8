// The hair base on a turning head (data/scenes/bob.json): at five head angles no skin shows inside
// the visible scalp, and no wisp shows a cut end at its root. Without the base and the root taper
// the same frames show skin there, so the check can fail.
#include <catch2/catch.hpp>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "apps/render/render_pipeline.hpp"
#include "apps/render/scene_frames.hpp"
#include "image_checks.hpp"
#include "run_command.hpp"
#include "scene_fixture.hpp"
#include "vector/polygon.hpp"

namespace render = wisp::render;
namespace vector = wisp::vector;
using Eigen::Vector2d;
using wisp::test::distance_to_rings;

namespace {

const std::string kScene = WISP_SOURCE_DIR "/data/scenes/bob.json";
constexpr int kSize = 320;

const render::SceneFrames& frames() {
  return wisp::test::loaded_scene(kScene, kSize);
}

std::vector<int> five_angles() {
  return wisp::test::five_angles(frames().anim);
}

struct Check {
  int inside = 0;    // pixels inside the visible scalp, 2 px or more from its boundary
  int skin = 0;      // of which show skin
  int cut_ends = 0;  // wisps with a root cap
  double yaw_deg = 0;
};

Check check_frame(int k, bool base_and_taper) {
  const render::SceneFrames& sf = frames();
  render::FrameSetup setup = render::frame_setup(sf.scene);
  if (!base_and_taper) setup.style.geometry.root_taper = 0;
  // The scalp region, traced whatever the style, for the check.
  const vector::HairBase scalp = render::frame_base(sf, k);
  const std::vector<vector::Occluder> occluders = render::frame_occluders(sf, k);
  const render::FrameResult r =
      render::render_frame(sf.projected[k], render::frame_body(sf, k), occluders,
                           base_and_taper ? scalp : vector::HairBase{}, setup, nullptr);
  const std::vector<std::uint8_t> rgba = render::rasterize_frame(r.picture);
  const Eigen::Vector3f skin = sf.scene.render.skin_color, shade = skin * 0.72f;
  Check c;
  std::vector<std::uint8_t> in(size_t(kSize) * kSize, 0);
  vector::fill_centres(in, kSize, kSize, scalp.rings, std::uint8_t(1));
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const Vector2d p(x + 0.5, y + 0.5);
      if (!in[size_t(y) * kSize + x] || distance_to_rings(scalp.rings, p) < 2) continue;
      // Visible: no part of the body (the neck, a shoulder) nearer than the scalp there.
      bool hidden = false;
      for (const vector::Occluder& o : occluders)
        hidden |= vector::inside_polygon(o.ring, p) && o.depth(p) < scalp.depth(p);
      if (hidden) continue;
      ++c.inside;
      const std::uint8_t* px = &rgba[4 * (size_t(y) * kSize + x)];
      const Eigen::Vector3f v(px[0] / 255.f, px[1] / 255.f, px[2] / 255.f);
      c.skin += std::min((v - skin).norm(), (v - shade).norm()) < 0.06f;
    }
  for (const vector::Wisp& w : r.wisps)
    c.cut_ends += std::count(w.outline.side.begin(), w.outline.side.end(), vector::Side::Root) > 0;
  const Eigen::Vector3d f = sf.anim.frames[k].head.rotation * Eigen::Vector3d::UnitZ();
  c.yaw_deg = std::atan2(f.x(), f.z()) * 180 / M_PI;
  return c;
}

}  // namespace

TEST_CASE("no skin shows inside the visible scalp and no root shows a cut end, at five angles",
          "[render][base]") {
  const std::vector<int> ks = five_angles();
  double lo = INFINITY, hi = -INFINITY;
  for (int k : ks) {
    const Check c = check_frame(k, true);
    INFO("frame " << k << ", head yaw " << c.yaw_deg << " degrees");
    lo = std::min(lo, c.yaw_deg), hi = std::max(hi, c.yaw_deg);
    CHECK(c.inside > 400);  // the scalp shows (600 to 3900 px of 320^2)
    CHECK(c.skin == 0);
    CHECK(c.cut_ends == 0);
  }
  CHECK(hi - lo > 40);  // the five angles span the turn
  // Without the base and the taper, skin shows between the roots and roots end square.
  const Check before = check_frame(ks[2], false);
  CHECK(before.skin > 40);  // 79 of its 2000 scalp pixels
  CHECK(before.cut_ends > 100);
}

TEST_CASE("the occluders and the hair base made from one set of head rays are those made apart",
          "[render][base]") {
  const render::SceneFrames& sf = frames();
  const int k = five_angles()[1];
  const auto head = render::frame_head_rays(sf, k);
  REQUIRE(head);
  const std::vector<vector::Occluder> apart = render::frame_occluders(sf, k),
                                      shared = render::frame_occluders(sf, k, head);
  const vector::HairBase base_apart = render::frame_base(sf, k),
                         base_shared = render::frame_base(sf, k, head);
  REQUIRE(apart.size() == shared.size());
  REQUIRE(apart.size() >= 2);  // the head and the neck at least
  CHECK(base_apart.rings == base_shared.rings);
  for (size_t o = 0; o < apart.size(); ++o) CHECK(apart[o].ring == shared[o].ring);
  int hits = 0;
  for (int y = 0; y < kSize; y += 5)
    for (int x = 0; x < kSize; x += 5) {
      const Vector2d p(x + 0.5, y + 0.5);
      for (size_t o = 0; o < apart.size(); ++o) {
        const double d = apart[o].depth(p);
        CHECK(d == shared[o].depth(p));
        hits += std::isfinite(d);
      }
      CHECK(base_apart.depth(p) == base_shared.depth(p));
    }
  CHECK(hits > 500);
}
