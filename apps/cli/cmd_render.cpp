// `wisp render scene.json -o OUTDIR`: the main job. Simulates (or reads a saved animation),
// projects every frame, then renders frames in parallel to PNG and SVG, followed by a preview
// video, a contact sheet and stats.json.
//
// Determinism and resuming. Each frame's solve is warm-started from the previous frame's answer,
// but only inside fixed blocks of frames (render.warm_start_block, counted from frame 0): blocks
// are independent, so they render in parallel and the pixels do not depend on the thread count.
// A frame is written to a temporary name and renamed; frames whose PNG and SVG both exist are
// skipped (unless --force), and when a block is resumed in its middle, its earlier frames are
// solved again in memory so that the warm starts, and therefore the pixels, are the same as in
// an uninterrupted run. The same holds for --frames ranges that split an animation across
// machines.
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <regex>
#include <stdexcept>

#include "apps/cli/commands.hpp"
#include "apps/render/picture.hpp"
#include "apps/render/progress.hpp"
#include "apps/render/render_pipeline.hpp"
#include "apps/render/scene_frames.hpp"
#include "io/anim_file.hpp"
#include "io/atomic_file.hpp"
#include "io/contact_sheet.hpp"
#include "io/scene.hpp"
#include "io/video_file.hpp"
#include "sim/body.hpp"
#include "sim/camera.hpp"
#include "sim/simulate.hpp"

namespace wisp::cli {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

struct RenderArgs {
  std::string scene, outdir, frames, size, anim, svg_style = "embedded";
  int threads = 0;
  bool force = false, quiet = false, masks = false;
};

std::string frame_name(int k, const char* ext) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "frame_%04d.%s", k, ext);
  return buf;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

struct FrameRecord {
  int frame = 0;
  nlohmann::json stats;
};

void run_render(const RenderArgs& a) {
  const auto t_start = Clock::now();
  std::unique_ptr<tbb::global_control> threads;
  if (a.threads > 0)
    threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                    size_t(a.threads));

  // Arguments first, so that their errors come before any work.
  int first = 0, last = -1;  // [first, last) ; last < 0: to the end
  if (!a.frames.empty()) {
    std::smatch m;
    if (!std::regex_match(a.frames, m, std::regex(R"((\d{1,6}):(\d{1,6}))")))
      throw std::invalid_argument("--frames: expected A:B (frames A to B-1), got '" + a.frames +
                                  "'");
    first = std::stoi(m[1]);
    last = std::stoi(m[2]);
    if (last <= first)
      throw std::invalid_argument("--frames " + a.frames + ": B must be greater than A");
  }
  const auto [width, height] =
      a.size.empty() ? std::pair<int, int>{0, 0} : render::parse_size("--size", a.size);
  if (a.svg_style != "embedded" && a.svg_style != "flat")
    throw std::invalid_argument("--svg-style: expected 'embedded' or 'flat', got '" + a.svg_style +
                                "'");

  // Validate the scene before touching the output folder.
  (void)io::load_scene(a.scene);
  // Output folder: created if missing, and it must take files.
  const fs::path out(a.outdir);
  std::error_code ec;
  fs::create_directories(out, ec);
  if (!fs::is_directory(out))
    throw std::runtime_error(a.outdir + ": cannot create the output folder");
  // Temporary files left by a killed render of this range are garbage: their frames get
  // rendered again. (Other ranges may be rendering into the same folder right now: their
  // temporaries are left alone.)
  for (const auto& entry : fs::directory_iterator(out, ec)) {
    std::smatch m;
    const std::string name = entry.path().filename().string();
    if (std::regex_match(name, m, std::regex(R"(\.(frame|mask)_(\d+)\.partial-\d+\.(png|svg))")) &&
        std::stoi(m[2]) >= first && (last < 0 || std::stoi(m[2]) < last))
      fs::remove(entry.path(), ec);
  }

  // The animation (simulated now, or read back) and every frame projected, in order.
  auto t0 = Clock::now();
  std::unique_ptr<render::ProgressBar> sim_bar;
  render::SceneFramesOptions load;
  load.anim = a.anim;
  load.width = width;
  load.height = height;
  load.sim_progress = [&](int done, int total) {
    if (a.quiet) return;
    if (!sim_bar) sim_bar = std::make_unique<render::ProgressBar>("simulate", total);
    sim_bar->update(done);
  };
  const render::SceneFrames frames = render::load_scene_frames(a.scene, load);
  if (sim_bar) sim_bar->finish();
  const io::Scene& scene = frames.scene;
  const sim::Animation& anim = frames.anim;
  const double load_ms = ms_since(t0);
  const int n = frames.frame_count();
  if (last < 0) last = n;
  if (first >= n || last > n)
    throw std::invalid_argument("--frames " + std::to_string(first) + ":" + std::to_string(last) +
                                ": the animation has " + std::to_string(n) +
                                " frames (0:" + std::to_string(n) + ")");

  render::FrameSetup setup = render::frame_setup(scene);
  setup.flat_regions = a.svg_style == "flat";
  const render::SvgStyle svg_style =
      setup.flat_regions ? render::SvgStyle::Flat : render::SvgStyle::Embedded;

  const auto done = [&](int k) {
    return fs::exists(out / frame_name(k, "png")) && fs::exists(out / frame_name(k, "svg"));
  };
  std::vector<char> todo(n, 0);
  int todo_count = 0;
  for (int k = first; k < last; ++k)
    if (a.force || !done(k)) todo[k] = 1, ++todo_count;

  const int block = std::max(1, scene.render.warm_start_block);
  std::vector<int> blocks;
  for (int b = first / block; b * block < last; ++b) {
    bool any = false;
    for (int k = std::max(first, b * block); k < std::min(last, (b + 1) * block); ++k)
      any |= todo[k];
    if (any) blocks.push_back(b);
  }

  std::mutex mutex;
  std::vector<FrameRecord> records;
  std::unique_ptr<render::ProgressBar> bar;
  if (!a.quiet && todo_count > 0) bar = std::make_unique<render::ProgressBar>("render", todo_count);
  int rendered = 0;
  const auto t_frames = Clock::now();
  tbb::parallel_for(size_t(0), blocks.size(), [&](size_t bi) {
    const int b = blocks[bi];
    int end = (b + 1) * block;
    while (end > b * block && !(end - 1 < n && todo[end - 1])) --end;  // last todo + 1
    std::vector<float> warm;
    for (int k = b * block; k < end; ++k) {
      const auto t_frame = Clock::now();
      render::FrameResult r = render::render_frame(
          frames.projected[k], render::frame_body(frames, k), render::frame_occluders(frames, k),
          render::frame_base(frames, k), setup, warm.empty() ? nullptr : &warm);
      warm = std::move(r.solution);
      if (!todo[k]) continue;  // solved only to warm-start the next frame of the block
      const auto t_write = Clock::now();
      render::write_frame_png(r.picture, out / frame_name(k, "png"));
      render::write_frame_svg(r.picture, out / frame_name(k, "svg"), svg_style);
      if (a.masks)
        render::write_mask_png(r.picture.mask, r.picture.width, r.picture.height,
                               out / ("mask" + frame_name(k, "png").substr(5)));
      const double write_ms = ms_since(t_write);
      nlohmann::json j = {{"frame", k},
                          {"time", anim.frames[k].time},
                          {"strands", frames.projected[k].strands.size()},
                          {"wisps", r.wisps.size()},
                          {"visible_curves", r.curves.size()},
                          {"curve_kinds",
                           {{"outlines", r.curve_stats.outlines},
                            {"centre_lines", r.curve_stats.centre_lines},
                            {"band_edges", r.curve_stats.band_edges},
                            {"highlights", r.curve_stats.highlights},
                            {"base", r.base_curves}}},
                          {"ink_strokes", r.picture.ink.size()},
                          {"faces", r.arrangement.stats.faces},
                          {"edges", r.arrangement.stats.edges},
                          {"intersections", r.arrangement.stats.intersections},
                          {"solver_cycles", r.solve.cycles},
                          {"solver_residual", r.solve.final_residual},
                          {"solver_converged", r.solve.converged || r.curves.empty()},
                          {"ms",
                           {{"wisps", r.time.wisps},
                            {"arrangement", r.time.arrangement},
                            {"arrangement_sweep", r.arrangement.stats.sweep_ms},
                            {"arrangement_resolve", r.arrangement.stats.resolve_ms},
                            {"curves", r.time.curves},
                            {"ink", r.time.ink},
                            {"rasterize", r.time.rasterize},
                            {"solve", r.time.solve},
                            {"write", write_ms},
                            {"frame", ms_since(t_frame)}}}};
      std::lock_guard<std::mutex> lock(mutex);
      records.push_back({k, std::move(j)});
      if (bar) bar->update(++rendered);
    }
  });
  if (bar) bar->finish();
  const double frames_ms = ms_since(t_frames);

  // Preview video and contact sheet of the whole range (frames rendered earlier included).
  std::vector<fs::path> pngs;
  std::vector<int> numbers;
  for (int k = first; k < last; ++k) {
    pngs.push_back(out / frame_name(k, "png"));
    numbers.push_back(k);
  }
  t0 = Clock::now();
  if (scene.render.video) io::write_video(out / "preview.mp4", pngs, anim.fps);
  io::ContactSheetOptions sheet;
  sheet.columns = scene.render.contact_sheet_columns;
  io::write_contact_sheet(out / "contact.png", pngs, numbers, sheet);
  const double outputs_ms = ms_since(t0);

  std::sort(records.begin(), records.end(),
            [](const FrameRecord& x, const FrameRecord& y) { return x.frame < y.frame; });
  nlohmann::json per_frame = nlohmann::json::array();
  std::map<std::string, std::vector<double>> stage;
  for (const FrameRecord& r : records) {
    per_frame.push_back(r.stats);
    for (const auto& [name, ms] : r.stats["ms"].items()) stage[name].push_back(ms.get<double>());
  }
  nlohmann::json medians, totals;
  for (const auto& [name, v] : stage) {
    medians[name] = median(v);
    double sum = 0;
    for (double x : v) sum += x;
    totals[name] = sum;
  }
  const nlohmann::json stats = {
      {"scene", a.scene},
      {"frames_in_animation", n},
      {"range", {first, last}},
      {"rendered", records.size()},
      {"skipped", (last - first) - int(records.size())},
      {"width", scene.camera.width},
      {"height", scene.camera.height},
      {"ms",
       {{"simulate_and_project", load_ms},
        {"frames", frames_ms},
        {"video_and_contact_sheet", outputs_ms},
        {"total", ms_since(t_start)}}},
      {"frames_per_second", frames_ms > 0 ? records.size() * 1000.0 / frames_ms : 0.0},
      {"stage_ms_median", medians},
      {"stage_ms_total", totals},
      {"frames", per_frame}};
  io::write_text_atomically(out / "stats.json", stats.dump(2) + "\n");
  if (!a.quiet)
    std::fprintf(stderr, "render: %d frames written, %d already there; output in %s\n",
                 int(records.size()), (last - first) - int(records.size()),
                 fs::absolute(out).string().c_str());
}

}  // namespace

void add_render_command(CLI::App& app) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand(
      "render", "Simulate a scene (or read a saved animation) and render its frames");
  cmd->add_option("scene", args->scene, "Scene file (.json)")->required();
  cmd->add_option("-o,--output", args->outdir, "Output folder")->required();
  cmd->add_option("--frames", args->frames, "Frames A to B-1, as A:B (default: all)");
  cmd->add_option("--size", args->size, "Image size WxH (default: the scene camera's)");
  cmd->add_option("--anim", args->anim,
                  "Render this saved animation (.wsim) instead of simulating");
  cmd->add_option("--svg-style", args->svg_style,
                  "embedded: shading as an image clipped by the silhouette; flat: a gradient "
                  "path per visible wisp region");
  cmd->add_option("--threads", args->threads, "Worker threads (default: all cores)")
      ->check(CLI::Range(1, 256));
  cmd->add_flag("--force", args->force, "Render frames that already exist again");
  cmd->add_flag("--masks", args->masks, "Also write each frame's hair mask (mask_NNNN.png)");
  cmd->add_flag("-q,--quiet", args->quiet, "No progress output");
  cmd->callback([args] { run_render(*args); });
}

}  // namespace wisp::cli
