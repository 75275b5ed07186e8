// `wisp assemble OUTDIR`: the last step of a render split into ranges, by a farm's tasks or by
// hand on several machines (`wisp render --frames A:B --no-previews --stats OUTDIR/stats/NAME.json`
// into one folder): checks that every frame is there, then writes the preview video, the contact
// sheet, on request animation.svg, and one stats.json merged from OUTDIR/stats/*.json
// (render::merged_stats).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/cli/commands.hpp"
#include "apps/render/render_range.hpp"
#include "apps/render/render_stats.hpp"
#include "diffusion/timer.hpp"
#include "io/anim_file.hpp"
#include "io/atomic_file.hpp"
#include "io/scene.hpp"

namespace wisp::cli {
namespace {

namespace fs = std::filesystem;

struct AssembleArgs {
  std::string outdir, scene, anim;
  bool quiet = false, animated_svg = false;
};

nlohmann::json read_json(const fs::path& file) {
  std::ifstream in(file);
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(file.string() + ": not JSON (" + e.what() + ")");
  }
}

// "3, 4, 5, 9" (the first few of them).
std::string list_frames(const std::vector<int>& frames) {
  std::string out;
  for (size_t i = 0; i < frames.size() && i < 12; ++i)
    out += (i ? ", " : "") + std::to_string(frames[i]);
  return frames.size() > 12 ? out + ", ..." : out;
}

// The runs' stats files, oldest first (a resumed task's file is newer and wins on its frames).
std::vector<render::RunStatsFile> run_stats_files(const fs::path& folder) {
  std::vector<fs::path> files;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(folder, ec))
    if (entry.path().extension() == ".json") files.push_back(entry.path());
  std::sort(files.begin(), files.end(), [](const fs::path& a, const fs::path& b) {
    const auto ta = fs::last_write_time(a), tb = fs::last_write_time(b);
    return ta != tb ? ta < tb : a < b;
  });
  std::vector<render::RunStatsFile> runs;
  for (const fs::path& f : files) runs.push_back({f.string(), read_json(f)});
  return runs;
}

void run_assemble(const AssembleArgs& a) {
  const auto t_start = diffusion::Clock::now();
  const fs::path out(a.outdir);
  if (!fs::is_directory(out)) throw std::runtime_error(a.outdir + ": no such folder");
  // The scene and animation: as given, else as the farm recorded them.
  nlohmann::json farm;
  if (fs::exists(out / "farm.json")) farm = read_json(out / "farm.json");
  const std::string scene_file = !a.scene.empty() ? a.scene : farm.value("scene", "");
  if (scene_file.empty())
    throw std::runtime_error(a.outdir + ": no farm.json to name the scene: give it with --scene");
  const fs::path anim_file = !a.anim.empty() ? fs::path(a.anim) : out / "anim.wsim";
  const io::Scene scene = io::load_scene(scene_file);
  const sim::Animation anim = io::read_animation(anim_file);
  const render::FrameRange range{0, int(anim.frames.size())};

  const std::vector<int> missing = render::missing_frames(out, range);
  if (!missing.empty())
    throw std::runtime_error(a.outdir + ": " + std::to_string(missing.size()) + " of " +
                             std::to_string(range.size()) + " frames missing (" +
                             list_frames(missing) +
                             "): render them first (`wisp farm status` names the tasks)");
  const auto t_previews = diffusion::Clock::now();
  render::write_previews(scene, anim.fps, range, out);
  const double previews_ms = diffusion::ms_since(t_previews);
  double animated_svg_ms = 0;
  if (a.animated_svg) {
    const auto t_svg = diffusion::Clock::now();
    render::write_animated_svg(anim.fps, range, out);
    animated_svg_ms = diffusion::ms_since(t_svg);
  }
  const std::vector<render::RunStatsFile> runs = run_stats_files(out / "stats");
  nlohmann::json stats = render::merged_stats(runs, scene_file, scene, range.size(), range,
                                              previews_ms, render::range_records(out, range, {}));
  stats["ms"]["assemble"] = diffusion::ms_since(t_start);
  if (a.animated_svg) stats["ms"]["animated_svg"] = animated_svg_ms;
  io::write_text_atomically(out / "stats.json", stats.dump(2) + "\n");
  if (!a.quiet)
    std::fprintf(stderr, "assemble: %d frames, %s%s contact.png and stats.json (%zu runs) in %s\n",
                 range.size(), scene.render.video ? "preview.mp4," : "",
                 a.animated_svg ? " animation.svg," : "", runs.size(),
                 fs::absolute(out).string().c_str());
}

}  // namespace

void add_command(CLI::App& app, const std::vector<std::string>&) {
  auto args = std::make_shared<AssembleArgs>();
  CLI::App* cmd = add_subcommand(app, "assemble");
  cmd->add_option("outdir", args->outdir, "The folder holding every frame")->required();
  cmd->add_option("--scene", args->scene, "Scene file (default: the one farm.json names)");
  cmd->add_option("--anim", args->anim, "Saved animation (default: OUTDIR/anim.wsim)");
  cmd->add_flag("--animated-svg", args->animated_svg,
                "Also write animation.svg: every frame's SVG as one animated SVG");
  cmd->add_flag("-q,--quiet", args->quiet, "No summary line");
  cmd->callback([args] { run_assemble(*args); });
}

}  // namespace wisp::cli
