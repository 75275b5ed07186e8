// Frames streamed while they are read (render::stream_scene_frames, what `wisp render` renders
// from) are those loaded whole (render::load_scene_frames, what the inspector shows): the same
// projection of every frame, bit for bit, the same head poses and the same hair base.
#include <catch2/catch.hpp>
#include <string>

#include "apps/render/scene_frames.hpp"
#include "io/scene.hpp"
#include "run_command.hpp"

namespace render = wisp::render;

namespace {

const std::string scene = WISP_SOURCE_DIR "/data/scenes/default.json";

// 48x48 frames of the default scene, from its simulated animation.
render::SceneFramesOptions small_frames() {
  render::SceneFramesOptions o;
  o.anim = wisp::test::simulated(scene);
  o.width = o.height = 48;
  return o;
}

}  // namespace

TEST_CASE("streamed frames are the frames loaded whole", "[render]") {
  render::SceneFramesOptions o = small_frames();
  const render::SceneFrames whole = render::load_scene_frames(scene, o);
  const auto streamed = render::stream_scene_frames(wisp::io::load_scene(scene), o);
  REQUIRE(streamed->frame_count() == whole.frame_count());
  for (int k = 0; k < whole.frame_count(); ++k) {
    INFO("frame " << k);
    streamed->wait_for(k);
    const wisp::sim::ProjectedFrame &a = streamed->projected[k], &b = whole.projected[k];
    CHECK(a.frame == b.frame);
    CHECK(a.focal_px == b.focal_px);
    CHECK(streamed->anim.frames[k].time == whole.anim.frames[k].time);
    CHECK(streamed->anim.frames[k].head.position == whole.anim.frames[k].head.position);
    REQUIRE(a.strands.size() == b.strands.size());
    bool same = true;
    for (size_t s = 0; s < a.strands.size(); ++s)
      same = same && a.strands[s].pixel == b.strands[s].pixel &&
             a.strands[s].visible == b.strands[s].visible &&
             a.strands[s].depth == b.strands[s].depth;
    CHECK(same);
    if (k == 0) CHECK(bool(streamed->scalp) == bool(whole.scalp));  // made with frame 0
  }
}

TEST_CASE("a stream asked for the first frames makes those and frame 1, not the rest", "[render]") {
  render::SceneFramesOptions o = small_frames();
  const render::SceneFrames whole = render::load_scene_frames(scene, o);
  o.needed = 1;  // frame 0 alone, whose motion neighbour is frame 1
  const auto streamed = render::stream_scene_frames(wisp::io::load_scene(scene), o);
  REQUIRE(streamed->frame_count() == whole.frame_count());
  REQUIRE(whole.frame_count() > 2);
  for (int k = 0; k < 2; ++k) {
    streamed->wait_for(k);
    CHECK(streamed->projected[k].strands.size() == whole.projected[k].strands.size());
    CHECK(streamed->projected[k].strands[0].pixel == whole.projected[k].strands[0].pixel);
  }
  CHECK_THROWS_WITH(streamed->wait_for(2), Catch::Contains("never made"));
  CHECK(streamed->projected[2].strands.empty());
}

TEST_CASE("a stream's frames are let go, its feed stopped first, the scene kept", "[render]") {
  const auto streamed = render::stream_scene_frames(wisp::io::load_scene(scene), small_frames());
  REQUIRE(streamed->frame_count() > 2);
  streamed->wait_for(0);  // the feed may still be making the later frames
  const int width = streamed->scene.camera.width;
  streamed->release_frames();  // stops the feed before the frames it fills go
  CHECK(!streamed->feed);
  CHECK(streamed->frame_count() == 0);
  CHECK(streamed->anim.frames.empty());
  CHECK(!streamed->body);
  CHECK(!streamed->scalp);
  CHECK(streamed->scene.camera.width == width);
  streamed->wait_for(5);  // no feed: returns at once
}
