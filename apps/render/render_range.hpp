// A range of an animation's frames rendered into a folder: frame_NNNN.png and frame_NNNN.svg per
// frame (and mask_NNNN.png on request), then the range's preview video and contact sheet. The job
// of `wisp render` below its command line.
//
// Determinism and resuming. Each frame's solve is warm-started from the previous frame's answer,
// but only inside fixed blocks of frames (render.warm_start_block, counted from frame 0), and
// frames are shaded in order, so the pixels do not depend on the thread count.
// A frame is written to a temporary name and renamed; frames whose PNG and SVG both exist are
// skipped (unless forced), and when a block is resumed in its middle, its earlier frames are
// solved again in memory so that the warm starts, and therefore the pixels, are the same as in
// an uninterrupted run. The same holds for ranges that split an animation across machines.
#pragma once

#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "apps/render/picture.hpp"
#include "apps/render/render_pipeline.hpp"
#include "apps/render/scene_frames.hpp"
#include "apps/render/svg_animation.hpp"

namespace wisp::render {

// Frames first to last - 1 of an animation.
struct FrameRange {
  int first = 0, last = 0;
  int size() const { return last - first; }
};

// The frames of warm-start block b (blocks of `block` frames counted from frame 0), the last
// block cut at frame_count.
FrameRange block_frames(int b, int block, int frame_count);

// An animation's frames cut into `parts` consecutive ranges of whole warm-start blocks, as even as
// whole blocks allow (the first ranges take one block more); fewer ranges when there are fewer
// blocks. Ranges that split at block boundaries solve no frame twice, and render the same pixels
// as one run over the whole animation (see the top of this file). `block` < 1 counts as 1.
std::vector<FrameRange> block_aligned_ranges(int frame_count, int block, int parts);

// The file of frame k: "frame_0007.png" for k = 7 and ext "png".
std::string frame_file_name(int k, const char* ext);

// Checks, without creating anything, that `folder` is a folder or can be created as one (its
// nearest existing ancestor is a writable folder). Throws std::runtime_error naming it.
void check_frame_folder(const std::filesystem::path& folder);

// Creates `folder` (and its .stats/ subfolder) if missing and removes the temporaries that a
// killed render left: those of frames first to last - 1 (last < 0: to the end), which get
// rendered again, and any other of ours whose process is gone (previews, stats). Temporaries of
// other ranges whose process still runs are left alone: it may be rendering into this folder.
// Throws std::runtime_error naming the folder when it cannot be created.
void prepare_frame_folder(const std::filesystem::path& folder, int first, int last);

// The peak memory of rendering `parallel` frames of width x height at once, estimated before
// any work: kRenderBaseBytes for the process and the scene, kRenderBytesPerPixel per pixel of
// each frame in flight (measured: docs/robustness.md).
constexpr double kRenderBaseBytes = 256.0 * (1 << 20);
constexpr double kRenderBytesPerPixel = 128;
double render_peak_bytes(int width, int height, int parallel);

// Which frames to write and which warm-start blocks to solve for them.
struct RangePlan {
  int block = 1;            // frames per warm-start block
  std::vector<char> write;  // per frame of the animation: 1 to write it
  std::vector<int> blocks;  // the blocks holding a frame to write, in order
  int write_count() const;
};

// The frames of `range` to write: all of them when `force`, else those whose PNG or SVG is
// missing from `folder`. `block`: render.warm_start_block (at least 1 is used).
RangePlan plan_range(const std::filesystem::path& folder, FrameRange range, int frame_count,
                     int block, bool force);

struct FrameFiles {
  std::filesystem::path folder;
  SvgStyle svg_style = SvgStyle::Embedded;
  bool masks = false;  // also write mask_NNNN.png
};

// Renders the planned frames into files.folder in a pipeline (TBB): the geometry of any frame
// (render_geometry) on a free core as soon as the frame is ready (SceneFrames::wait_for: frames
// may still be simulated), the solve (render_solve) one frame at a time in order, anti-aliasing
// (render_finish) on a free core again, while a writer thread (frame_writer.hpp) draws and writes
// the finished frames; a failed write ends the run with its error. `written(count)` is called after
// each frame written, one call at a time (for a progress bar). `before_writing`, when given, is
// called once on the writer thread before the first file is written (not at all when no frame
// is): checks whose answer comes while the first frame computes are awaited there, and what it
// throws ends the run before any file is written. Each frame's stats record (render_stats.hpp) is
// kept on disk beside it
// (.stats/frame_NNNN.json), so a resumed run still reports every frame. Returns the records of
// the frames written, in frame order.
std::vector<nlohmann::json> render_range(const SceneFrames& frames, const FrameSetup& setup,
                                         const RangePlan& plan, const FrameFiles& files,
                                         const std::function<void(int count)>& written,
                                         const std::function<void()>& before_writing = {});

// The records of every frame of `range` in `folder`: those of `written` (this run), else those
// kept on disk by earlier runs; frames with neither are left out. In frame order.
std::vector<nlohmann::json> range_records(const std::filesystem::path& folder, FrameRange range,
                                          const std::vector<nlohmann::json>& written);

// The preview video (when the scene asks for one, at `fps`) and the contact sheet of every frame
// of `range` in `folder`, those rendered by earlier runs (or other machines) included.
void write_previews(const io::Scene& scene, double fps, FrameRange range,
                    const std::filesystem::path& folder);

// animation.svg in `folder`: the SVGs of every frame of `range` there as one animated SVG at `fps`
// (apps/render/svg_animation.hpp), those rendered by earlier runs (or other machines) included.
SvgAnimationStats write_animated_svg(double fps, FrameRange range,
                                     const std::filesystem::path& folder);

// The frames of `range` whose PNG or SVG is missing from `folder`, in order.
std::vector<int> missing_frames(const std::filesystem::path& folder, FrameRange range);

}  // namespace wisp::render
