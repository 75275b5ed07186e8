// One frame as the inspector sees it: everything `wisp render` computes for the frame (wisps,
// arrangement with its faces, diffusion curves, rasterized constraints, solution, finished
// picture) plus what only an inspector wants: the solver residual at every pixel after each
// cycle, and the finished image and hair mask rasterized once. FrameSource renders frames on
// demand exactly as the renderer does, including its warm starts: inside a block of
// render.warm_start_block frames each solve starts from the previous frame's answer, so the
// inspector replays the frames before the asked one in its block (and remembers their answers,
// so stepping forward costs one frame).
#pragma once

#include <cstdint>
#include <map>
#include <vector>

#include "apps/render/render_pipeline.hpp"
#include "apps/render/scene_frames.hpp"

namespace wisp::inspect {

struct InspectFrame {
  int index = 0;
  double time = 0;
  render::FrameResult result;  // arrangement.view filled
  // Per solver step (after the FMG start, then after each cycle: the entries of
  // result.solve.residual_history): |b - A u| at every pixel, the largest over the channels.
  std::vector<std::vector<float>> residual;
  std::vector<std::uint8_t> image;  // the finished frame, RGBA (render::rasterize_frame)
  std::vector<std::uint8_t> mask;   // the anti-aliased hair mask, coverage 0-255 per pixel

  int width() const { return result.picture.width; }
  int height() const { return result.picture.height; }
};

class FrameSource {
 public:
  explicit FrameSource(render::SceneFrames frames);

  int frame_count() const { return frames_.frame_count(); }
  const render::SceneFrames& frames() const { return frames_; }

  // Frame k (0 <= k < frame_count()), rendered as `wisp render` renders it.
  InspectFrame render(int k);

 private:
  render::SceneFrames frames_;
  render::FrameSetup setup_;
  int block_ = 1;
  std::map<int, render::FrameSolution> solved_;  // solutions of frames of the current block
};

}  // namespace wisp::inspect
