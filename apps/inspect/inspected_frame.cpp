// Frames for the inspector, rendered with the renderer's warm starts (see inspect_frame.hpp).
#include "apps/inspect/inspected_frame.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace wisp::inspect {

FrameSource::FrameSource(render::SceneFrames frames)
    : frames_(std::move(frames)),
      setup_(render::frame_setup(frames_.scene)),
      block_(std::max(1, frames_.scene.render.warm_start_block)) {}

InspectFrame FrameSource::render(int k) {
  if (k < 0 || k >= frame_count())
    throw std::out_of_range("frame " + std::to_string(k) + ": the animation has " +
                            std::to_string(frame_count()) + " frames (0 to " +
                            std::to_string(frame_count() - 1) + ")");
  const int first = k / block_ * block_;
  for (auto it = solved_.begin(); it != solved_.end();)
    it = it->first < first || it->first >= first + block_ ? solved_.erase(it) : std::next(it);

  // The warm start: the answer of frame k-1 when k is not the first of its block, solved again
  // from the nearest remembered frame when needed (the body does not affect the solve).
  int from = first;
  for (int j = k - 1; j >= first; --j)
    if (solved_.count(j)) {
      from = j + 1;
      break;
    }
  for (int j = from; j < k; ++j) {
    const auto prev = solved_.find(j - 1);
    const render::FrameSolution* warm = prev != solved_.end() ? &prev->second : nullptr;
    solved_[j] = render::render_frame(frames_.projected[j], {}, render::frame_occluders(frames_, j),
                                      render::frame_base(frames_, j), setup_, warm,
                                      render::motion_neighbour(frames_, j))
                     .solution;
  }

  InspectFrame out;
  out.index = k;
  out.time = frames_.anim.frames[k].time;
  render::FrameSetup setup = setup_;
  setup.keep_faces = true;
  // The residual is of the solve's window (FrameResult::window): its three colour planes.
  setup.solver.observer = [&out](int, const std::vector<float>& r) {
    const size_t n = r.size() / 3;
    std::vector<float> magnitude(n, 0.0f);
    for (size_t c = 0; c < 3; ++c)
      for (size_t i = 0; i < n; ++i) magnitude[i] = std::max(magnitude[i], std::abs(r[c * n + i]));
    out.residual.push_back(std::move(magnitude));
  };
  const auto prev = solved_.find(k - 1);
  const render::FrameSolution* warm = k > first && prev != solved_.end() ? &prev->second : nullptr;
  out.result = render::render_frame(
      frames_.projected[k], render::frame_body(frames_, k), render::frame_occluders(frames_, k),
      render::frame_base(frames_, k), setup, warm, render::motion_neighbour(frames_, k));
  solved_[k] = out.result.solution;
  out.image = render::rasterize_frame(out.result.picture);
  out.mask = render::rasterize_mask(out.result.arrangement.mask, out.width(), out.height());
  return out;
}

}  // namespace wisp::inspect
