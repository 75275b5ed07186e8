// `wisp render scene.json -o OUTDIR`: the main job. Simulates (or reads a saved animation),
// projects every frame, then renders the frames in parallel to PNG and SVG, resumably, followed
// by a preview video, a contact sheet, stats.json and on request animation.svg
// (apps/render/render_range.hpp, render_stats.hpp). This file reads the command line, checks it and
// reports progress.
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <regex>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "apps/cli/commands.hpp"
#include "apps/cli/malloc_conf.hpp"
#include "apps/render/image_size.hpp"
#include "apps/render/progress.hpp"
#include "apps/render/render_range.hpp"
#include "apps/render/render_stats.hpp"
#include "apps/render/scene_frames.hpp"
#include "diffusion/timer.hpp"
#include "io/atomic_file.hpp"
#include "io/scene.hpp"
#include "io/video_file.hpp"
#include "sim/choices.hpp"

namespace wisp::cli {
namespace {

namespace fs = std::filesystem;
using diffusion::Clock;
using diffusion::ms_since;

struct RenderArgs {
  std::string scene, outdir, frames, size, anim, stats;
  std::string svg_style = sim::choice_name(render::SvgStyle::Embedded);
  int threads = 0;
  double max_memory_gib = 8;
  bool force = false, quiet = false, masks = false, no_previews = false, animated_svg = false;
};

// --frames A:B as (A, B); (0, -1) when not given: to the end.
std::pair<int, int> parse_frames(const std::string& text) {
  if (text.empty()) return {0, -1};
  std::smatch m;
  if (!std::regex_match(text, m, std::regex(R"((\d{1,6}):(\d{1,6}))")))
    throw std::invalid_argument("--frames: expected A:B (frames A to B-1), got '" + text + "'");
  const int first = std::stoi(m[1]), last = std::stoi(m[2]);
  if (last <= first) throw std::invalid_argument("--frames " + text + ": B must be greater than A");
  return {first, last};
}

// The frames asked for, checked against the animation's length.
render::FrameRange frame_range(std::pair<int, int> asked, int frame_count) {
  const render::FrameRange range{asked.first, asked.second < 0 ? frame_count : asked.second};
  if (range.first >= frame_count || range.last > frame_count)
    throw std::invalid_argument("--frames " + std::to_string(range.first) + ":" +
                                std::to_string(range.last) + ": the animation has " +
                                std::to_string(frame_count) +
                                " frames (0:" + std::to_string(frame_count) + ")");
  return range;
}

// The animation (simulated now, or read back) and its frames projected in order on a thread of
// their own, each ready for rendering as soon as it is made (render::stream_scene_frames). Scenes
// with fur are simulated whole first, with a progress bar. `needed` > 0: no frame from there on
// is rendered (SceneFramesOptions::needed).
std::unique_ptr<render::SceneFrames> simulate_and_project(io::Scene scene, const RenderArgs& a,
                                                          std::pair<int, int> size, int needed) {
  std::unique_ptr<render::ProgressBar> bar;
  render::SceneFramesOptions load;
  load.anim = a.anim;
  load.needed = needed;
  std::tie(load.width, load.height) = size;
  load.sim_progress = [&](int done, int total) {
    if (a.quiet) return;
    if (!bar) bar = std::make_unique<render::ProgressBar>("simulate", total);
    bar->update(done);
  };
  std::unique_ptr<render::SceneFrames> frames = render::stream_scene_frames(std::move(scene), load);
  if (bar) bar->finish();
  return frames;
}

// The planned frames rendered into the folder, with a progress bar. `first_written`: called once,
// when the first frame is written; `before_writing`: render::render_range's.
std::vector<nlohmann::json> render_frames(const render::SceneFrames& frames,
                                          const render::FrameSetup& setup,
                                          const render::RangePlan& plan,
                                          const render::FrameFiles& files, bool quiet,
                                          const std::function<void()>& first_written,
                                          const std::function<void()>& before_writing) {
  std::unique_ptr<render::ProgressBar> bar;
  const int count = plan.write_count();
  if (!quiet && count > 0) bar = std::make_unique<render::ProgressBar>("render", count);
  std::vector<nlohmann::json> written = render::render_range(
      frames, setup, plan, files,
      [&](int done) {
        if (done == 1) first_written();
        if (bar) bar->update(done);
      },
      before_writing);
  if (bar) bar->finish();
  return written;
}

std::string gib(double bytes) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f GiB", bytes / double(1 << 30));
  return buf;
}

// How many frames may render at once within --max-memory (at most `threads`); throws naming the
// size's origin (`field`) when even one frame does not fit.
int frames_in_memory(const RenderArgs& a, const std::string& field, int width, int height,
                     int threads) {
  const double limit = a.max_memory_gib * double(1 << 30);
  if (render::render_peak_bytes(width, height, 1) > limit)
    throw std::invalid_argument(
        field + ": a " + std::to_string(width) + "x" + std::to_string(height) +
        " frame needs about " + gib(render::render_peak_bytes(width, height, 1)) +
        ", above --max-memory " + gib(limit) + "; lower the size or raise --max-memory");
  int parallel = std::max(1, threads);
  while (parallel > 1 && render::render_peak_bytes(width, height, parallel) > limit) --parallel;
  return parallel;
}

void run_render(const RenderArgs& a) {
  const auto t_start = Clock::now();

  // Arguments first, so that their errors come before any work; the scene before the output
  // folder is touched.
  const std::pair<int, int> asked = parse_frames(a.frames);
  const std::pair<int, int> size =
      a.size.empty() ? std::pair<int, int>{0, 0} : render::parse_size("--size", a.size);
  // CLI11 checked the name against the table (IsMember).
  const render::SvgStyle svg_style = *sim::parse_choice<render::SvgStyle>(a.svg_style);
  io::Scene scene = io::load_scene(a.scene);
  const fs::path out(a.outdir);
  render::check_frame_folder(out);

  // The size's budgets before any work: memory (fewer frames at once when all would not fit)
  // and the video encoder (which refuses some sizes only after every frame was written).
  const int width = size.first > 0 ? size.first : scene.camera.width;
  const int height = size.first > 0 ? size.second : scene.camera.height;
  const std::string size_field =
      size.first > 0 ? "--size " + a.size : a.scene + ": camera.width x camera.height";
  const int cores = a.threads > 0 ? a.threads : tbb::info::default_concurrency();
  const int parallel = frames_in_memory(a, size_field, width, height, cores);
  const tbb::global_control threads(tbb::global_control::max_allowed_parallelism, size_t(parallel));
  // The video check runs on a thread beside the first frames, and its answer is awaited
  // before anything is written: the frame folder is made and the first frame written only then,
  // so a size the encoder refuses still writes nothing (docs/performance.md, "First frame").
  std::optional<io::VideoCheck> video;
  if (scene.render.video && !a.no_previews)  // --no-previews writes no video: needs no module
    video.emplace(out / "preview.mp4", width, height, scene.sim.fps);
  const auto await_video = [&] {
    if (!video) return;
    try {
      video->wait();
    } catch (const io::VideoModuleError&) {
      throw;  // not the size's fault
    } catch (const std::exception& e) {
      throw std::invalid_argument(size_field + ": " + e.what());
    }
  };
  bool folder_ready = false;
  const auto before_writing = [&] {
    await_video();
    render::prepare_frame_folder(out, asked.first, asked.second);
    folder_ready = true;
  };
  // Scenes with fur are simulated whole before the first frame: a refused size is reported
  // before that work, and the probe has nothing to overlap with.
  if (scene.fur.count > 0) await_video();

  auto t0 = Clock::now();
  const std::unique_ptr<render::SceneFrames> loaded =
      simulate_and_project(std::move(scene), a, size, std::max(0, asked.second));
  const render::SceneFrames& frames = *loaded;
  render::RunTimes ms;
  ms.simulate_and_project = ms_since(t0);
  const render::FrameRange range = frame_range(asked, frames.frame_count());

  render::FrameSetup setup = render::frame_setup(frames.scene);
  setup.flat_regions = svg_style == render::SvgStyle::Flat;
  const render::RangePlan plan = render::plan_range(out, range, frames.frame_count(),
                                                    frames.scene.render.warm_start_block, a.force);
  t0 = Clock::now();
  const std::vector<nlohmann::json> written = render_frames(
      frames, setup, plan, {out, svg_style, a.masks}, a.quiet,
      [&] { ms.first_frame = ms_since(t_start); }, before_writing);
  ms.frames = ms_since(t0);
  if (!folder_ready) before_writing();  // every frame was there: the previews are written next
  // Frames are simulated while the first ones render: the feed's own time, to its last frame.
  if (frames.feed) ms.simulate_and_project += frames.feed->ms();
  // The previews read the frames back from their files. The animation, its projections and the
  // pages the frames freed go before the video encoder allocates, which the freed pages do not
  // serve: the simulated default scene at 1024^2 peaked there at 313-319 MB, against 245 MB for
  // its frames.
  const double fps = frames.anim.fps;
  const int frame_count = frames.frame_count();
  loaded->release_frames();
  if (!a.no_previews) return_free_pages();

  t0 = Clock::now();
  if (!a.no_previews) render::write_previews(frames.scene, fps, range, out);
  ms.video_and_contact_sheet = ms_since(t0);
  if (a.animated_svg) {
    t0 = Clock::now();
    render::write_animated_svg(fps, range, out);
    ms.animated_svg = ms_since(t0);
  }
  ms.total = ms_since(t_start);
  const fs::path stats = a.stats.empty() ? out / "stats.json" : fs::path(a.stats);
  if (stats.has_parent_path()) fs::create_directories(stats.parent_path());
  const std::vector<nlohmann::json> records = render::range_records(out, range, written);
  io::write_text_atomically(stats, render::run_stats(a.scene, frames.scene, frame_count, range,
                                                     records, int(written.size()), ms)
                                           .dump(2) +
                                       "\n");
  if (!a.quiet)
    std::fprintf(stderr, "render: %d frames written, %d already there; output in %s\n",
                 int(written.size()), range.size() - int(written.size()),
                 fs::absolute(out).string().c_str());
}

}  // namespace

void add_command(CLI::App& app, const std::vector<std::string>&) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd = add_subcommand(app, "render");
  cmd->add_option("scene", args->scene, "Scene file (.json)")->required();
  cmd->add_option("-o,--output", args->outdir, "Output folder")->required();
  cmd->add_option("--frames", args->frames, "Frames A to B-1, as A:B (default: all)");
  cmd->add_option("--size", args->size, "Image size WxH (default: the scene camera's)");
  cmd->add_option("--anim", args->anim,
                  "Render this saved animation (.wsim) instead of simulating");
  cmd->add_option("--svg-style", args->svg_style,
                  "embedded: shading as an image clipped by the silhouette; flat: a gradient "
                  "path per visible wisp region")
      ->check(CLI::IsMember(sim::choice_names<render::SvgStyle>()));
  cmd->add_option("--threads", args->threads, "Worker threads (default: all cores)")
      ->check(CLI::Range(1, 256));
  cmd->add_option("--stats", args->stats,
                  "Write the run's stats here (default: OUTDIR/stats.json); `wisp assemble` "
                  "merges OUTDIR/stats/*.json");
  cmd->add_flag("--no-previews", args->no_previews,
                "No preview video or contact sheet (several renders share the folder: `wisp "
                "assemble` writes them)");
  cmd->add_option("--max-memory", args->max_memory_gib,
                  "Memory budget in GiB (default 8): fewer frames render at once above it, and a "
                  "frame that alone needs more is refused before any work")
      ->check(CLI::Range(0.001, 1e6));
  cmd->add_flag("--animated-svg", args->animated_svg,
                "Also write animation.svg: the frames' SVGs as one animated SVG that plays in a "
                "browser, in the --svg-style of the frames");
  cmd->add_flag("--force", args->force, "Render frames that already exist again");
  cmd->add_flag("--masks", args->masks, "Also write each frame's hair mask (mask_NNNN.png)");
  cmd->add_flag("-q,--quiet", args->quiet, "No progress output");
  cmd->callback([args] { run_render(*args); });
}

}  // namespace wisp::cli
