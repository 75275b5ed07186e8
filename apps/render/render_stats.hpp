// stats.json of `wisp render` (docs/render.md): per frame written, what it holds (strands, wisps,
// curves by kind, ink strokes, arrangement size, solver cycles and residual) and milliseconds per
// stage; for the run, the range, the frames written and skipped, the medians and totals of every
// stage over the frames, frames per second and the time of each phase.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "apps/render/render_pipeline.hpp"
#include "apps/render/render_range.hpp"
#include "apps/render/scene_frames.hpp"

namespace wisp::render {

// Frame k's record: `r` is its rendering, written in write_ms; frame_ms from the start of its
// rendering to the end of its writing.
nlohmann::json frame_stats(const SceneFrames& frames, int k, const FrameResult& r, double write_ms,
                           double frame_ms);

// Milliseconds of the phases of a run.
struct RunTimes {
  double simulate_and_project = 0;     // overlaps `frames` when the frames are streamed
  double first_frame = 0;              // from the start of the command to the first frame written
  double frames = 0;                   // rendering and writing the frames
  double video_and_contact_sheet = 0;  // the previews
  double animated_svg = 0;             // animation.svg (--animated-svg)
  double total = 0;
};

// The whole of stats.json. `scene`: as rendered (camera size overridden); `records`: every frame
// record of the range (frame_stats) in frame order, those of earlier runs included; `rendered`:
// how many of them this run wrote.
nlohmann::json run_stats(const std::string& scene_file, const io::Scene& scene,
                         int frames_in_animation, FrameRange range,
                         const std::vector<nlohmann::json>& records, int rendered,
                         const RunTimes& ms);

// One run's stats.json, read back for merging, and the file it came from.
struct RunStatsFile {
  std::string file;
  nlohmann::json stats;
};

// The stats.json of several runs that rendered parts of one animation into one folder (a farm's
// tasks, or machines rendering ranges by hand), for `wisp assemble`: one run over `range` whose
// frame records are the runs' merged by frame number, a later run's record replacing an earlier
// one's (a resumed task's); the image size is the runs'; "ms.frames" and the stage totals add up
// the runs' (machine time, not wall time), "ms.video_and_contact_sheet" is `previews_ms`, and
// "runs" lists each run's file, range, frames rendered and total milliseconds, in the order given.
// `kept`: the frame records kept beside the frames (render_range.hpp: range_records), for frames
// whose run wrote no stats.json (a task killed after writing them).
nlohmann::json merged_stats(const std::vector<RunStatsFile>& runs, const std::string& scene_file,
                            io::Scene scene, int frames_in_animation, FrameRange range,
                            double previews_ms, const std::vector<nlohmann::json>& kept);

}  // namespace wisp::render
