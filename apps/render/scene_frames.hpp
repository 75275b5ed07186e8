// From a scene file to the frames the renderer draws: the scene (with an optional image size
// override), its animation (simulated now, or read back from a saved .wsim), every frame projected
// in order (the occlusion hysteresis follows the frames, so frame k projects the same whichever
// frame a tool asks for first), the fur's springs run over the frames, and per frame the body under
// the hair and as occluder of it, and the hair base (the scalp under the wisps, sim/scalp.hpp,
// vector/hair_base.hpp). Shared by `wisp render` and `wisp-inspect`, so the inspector shows exactly
// the frames the renderer writes.
#pragma once

#include <condition_variable>
#include <exception>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "apps/render/body_paths.hpp"
#include "apps/render/picture.hpp"
#include "apps/render/render_pipeline.hpp"
#include "diffusion/timer.hpp"
#include "io/scene.hpp"
#include "sim/animation.hpp"
#include "sim/body.hpp"
#include "sim/fur.hpp"
#include "sim/projected.hpp"
#include "sim/scalp.hpp"
#include "vector/hair_base.hpp"

namespace wisp::render {

struct SceneFramesOptions {
  std::filesystem::path anim;  // a saved animation (.wsim) to read; empty: simulate the scene
  int width = 0, height = 0;   // > 0: render at this size instead of the camera's
  // Called while simulating (done, total), as sim::simulate's progress.
  std::function<void(int done, int total)> sim_progress;
  // stream_scene_frames only: > 0, the frames from `needed` on are not wanted (a render of frames
  // A:B); the feed ends after the last frame wanted or its motion neighbour (frame 1 for frame
  // 0), so a saved animation's later frames are not projected and a simulation stops there.
  // The frame count stays the animation's.
  int needed = 0;
};

// Frames made one after another on a thread of their own (stream_scene_frames): the animation
// simulated (or read) and each frame projected as soon as it is there, so that rendering starts
// on the first frames while the others are still simulated. Frame k is ready, with everything
// frame_body, frame_occluders, frame_base and motion_neighbour read for it, once wait_for(k)
// returns; an error of the simulation is rethrown by every wait after it.
class FrameFeed {
 public:
  explicit FrameFeed(int count) : count_(count) {}
  // Stops the thread at its next frame and waits for it.
  ~FrameFeed();
  FrameFeed(const FrameFeed&) = delete;
  FrameFeed& operator=(const FrameFeed&) = delete;

  // Runs `make` on the feed's thread; it publishes frames in order.
  void start(std::function<void(FrameFeed&)> make);
  // Frames 0 to ready - 1 are complete. Throws (ending `make`) when the feed is being stopped.
  void publish(int ready);
  // Blocks until frame k is ready; rethrows the thread's error.
  void wait_for(int k);
  // Milliseconds from start() to the last frame (so far, while still running).
  double ms() const;

 private:
  int count_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  int ready_ = 0;
  bool stopping_ = false, done_ = false;
  double ms_ = 0;
  diffusion::Clock::time_point start_;
  std::exception_ptr error_;
  std::thread thread_;
};

// SceneFrames' feed. A copy of SceneFrames holds the frames made so far and no feed: copy a
// streamed one only after waiting for its last frame.
class FeedOwner : public std::unique_ptr<FrameFeed> {
 public:
  using std::unique_ptr<FrameFeed>::operator=;
  FeedOwner() = default;
  FeedOwner(FeedOwner&&) = default;
  FeedOwner& operator=(FeedOwner&&) = default;
  FeedOwner(const FeedOwner&) : std::unique_ptr<FrameFeed>() {}
  FeedOwner& operator=(const FeedOwner&) = delete;
};

struct SceneFrames {
  io::Scene scene;  // camera size overridden when asked
  sim::Animation anim;
  std::vector<sim::ProjectedFrame> projected;  // one per animation frame
  std::shared_ptr<const sim::BodyModel> body;  // what render.body draws; null: nothing
  // The scalp of the hair base and the model whose head it lies on (`body` when there is one);
  // null when the style has no base.
  std::shared_ptr<const sim::Scalp> scalp;
  std::shared_ptr<const sim::BodyModel> head;
  // The scene's fur (sim/fur.hpp) and its tufts' tips per frame; null when it grows none.
  std::shared_ptr<const sim::FurModel> fur;
  sim::FurMotion fur_motion;

  // While frames are still being made (stream_scene_frames); null when all were made at load.
  // Last, so that its thread stops before the frames it fills are destroyed.
  FeedOwner feed;

  int frame_count() const { return int(projected.size()); }
  // Blocks until frame k is ready (see FrameFeed); returns at once without a feed.
  void wait_for(int k) const {
    if (feed) feed->wait_for(k);
  }
  // Lets go of the frames (the feed first, which stops its thread, then the animation, its
  // projections and the models), keeping `scene`: a render's previews come after its frames, and
  // the video encoder's buffers would otherwise come on top of them.
  void release_frames() {
    feed.reset();
    anim = {};
    projected = {};
    body.reset(), scalp.reset(), head.reset(), fur.reset();
    fur_motion = {};
  }
};

// Loads, simulates or reads, and projects. Errors are exceptions naming the file and field.
SceneFrames load_scene_frames(const std::filesystem::path& scene_path,
                              const SceneFramesOptions& options);
// The same for a scene already loaded (io::load_scene).
SceneFrames load_scene_frames(io::Scene scene, const SceneFramesOptions& options);

// The same, but returning once the frames' count is known: the frames are simulated (or read)
// and projected on a thread of their own (SceneFrames::feed), each ready as soon as it is made;
// the renderer waits for each frame it takes (SceneFrames::wait_for). The frames are those of
// load_scene_frames, bit for bit (up to `options.needed`). Scenes that grow fur are made whole
// before it returns (the fur's springs run over the whole shot); `options.sim_progress` is not
// called. Errors of the
// scene's files and fields are thrown here, the simulation's by the waits.
std::unique_ptr<SceneFrames> stream_scene_frames(io::Scene scene,
                                                 const SceneFramesOptions& options);

// The renderer's settings for a scene (style, solver tolerance, background).
FrameSetup frame_setup(const io::Scene& scene);

// The skin tones of a scene: render.skin_color where lit, 72 % of it in shadow.
BodyTones body_tones(const io::Scene& scene);

// The body under the hair in frame k: seamless paths of two flat skin tones, back to front, and
// the face's lines (apps/render/body_paths.hpp), and the fur's tufts (frame_fur).
BodyLayer frame_body(const SceneFrames& frames, int k);

// The fur's tufts in frame k (vector/fur.hpp): those within the style's fin band of the
// silhouette, or all in front with an interior opacity; none when the scene grows no fur.
std::vector<vector::FurTuft> frame_fur(const SceneFrames& frames, int k);

// Eye rays against the head in frame k, for frame_occluders and frame_base to share (each builds
// its own without them); null when neither needs the head.
std::shared_ptr<const sim::SurfaceRays> frame_head_rays(const SceneFrames& frames, int k);

// The head and body in frame k as occluders of the hair (apps/body_occluders.hpp); none when
// the scene draws no body. `head`: frame_head_rays(frames, k), or null.
std::vector<vector::Occluder> frame_occluders(const SceneFrames& frames, int k,
                                              std::shared_ptr<const sim::SurfaceRays> head = {});

// The hair base in frame k: the visible scalp traced on a grid of about 1/512 of the frame
// (at least 1 px); empty when the style has none. `head`: frame_head_rays(frames, k), or null.
vector::HairBase frame_base(const SceneFrames& frames, int k,
                            std::shared_ptr<const sim::SurfaceRays> head = {});

// The frame whose strands give frame k its motion, for the blur (vector::BlurSources): the one
// before, or the one after for the first; null when there is no other.
const sim::ProjectedFrame* motion_neighbour(const SceneFrames& frames, int k);

}  // namespace wisp::render
