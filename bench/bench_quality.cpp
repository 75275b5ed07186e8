// wisp-bench quality: how frames hold up at 1:1. For the default and curly scenes in every style
// preset, frame 40 is rendered at 512^2 and at 2048^2 (`wisp render`, as a user runs it), the
// large one box-filtered down, and the two compared inside the figure (apps/render/quality.hpp):
// the 99th percentile error, the share of pixels off by more than 32/255, the mean. The bar of
// the picture-at-1:1 work is p99 <= 12 and <= 0.3 % over 32.
//
// `wisp-bench quality [SIZE] [--style JSON]`: with --style, the JSON object's fields are set in
// each preset's style for the 1:1 render only (the 4x reference keeps the preset's own), so the
// bench shows what a style setting costs at 1:1: `--style '{"flatten_tolerance": 0.1}'`.
#include <unistd.h>

#include <charconv>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "apps/render/quality.hpp"
#include "bench/benches.hpp"

namespace wisp::bench {
namespace {

namespace fs = std::filesystem;

bool run_quiet(const std::string& cmd) {
  return std::system((cmd + " > /dev/null").c_str()) == 0;
}

}  // namespace

int run_quality(const std::vector<std::string>& args) {
  const fs::path exe_dir = fs::canonical("/proc/self/exe").parent_path();
  const std::string wisp = (exe_dir / "wisp").string();
  int size = 512;
  const int frame = 40;
  nlohmann::json style_override = nlohmann::json::object();
  for (size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--style") {
      if (i + 1 == args.size()) {
        std::fprintf(stderr, "wisp-bench quality: --style needs a JSON object\n");
        return 2;
      }
      style_override = nlohmann::json::parse(args[++i], nullptr, false);
      if (!style_override.is_object()) {
        std::fprintf(stderr, "wisp-bench quality: --style: not a JSON object: %s\n",
                     args[i].c_str());
        return 2;
      }
    } else {
      const char *first = args[i].data(), *last = first + args[i].size();
      const auto [end, error] = std::from_chars(first, last, size);
      if (error != std::errc() || end != last || size < 16 || size > 4096) {
        std::fprintf(stderr, "wisp-bench quality: size must be 16 to 4096, got '%s'\n",
                     args[i].c_str());
        return 2;
      }
    }
  }
  const fs::path dir =
      fs::temp_directory_path() / ("wisp_bench_quality_" + std::to_string(getpid()));
  fs::create_directories(dir);
  nlohmann::json results = nlohmann::json::array();
  for (const std::string scene_name : {"default", "curly"}) {
    const std::string scene = std::string(WISP_SOURCE_DIR "/data/scenes/") + scene_name + ".json";
    const std::string anim = (dir / (scene_name + ".wsim")).string();
    if (!run_quiet(wisp + " simulate " + scene + " -o " + anim + " -q")) {
      std::fprintf(stderr, "wisp-bench quality: simulating %s failed\n", scene.c_str());
      return 1;
    }
    for (const std::string preset : {"faraj", "toon", "anime", "soft"}) {
      std::fprintf(stderr, "quality bench: %s, %s\n", scene_name.c_str(), preset.c_str());
      nlohmann::json doc = nlohmann::json::parse(std::ifstream(scene));
      doc["style"] = {{"preset", preset}};
      doc["render"]["video"] = false;
      fs::path png[2];
      for (int k = 0; k < 2; ++k) {
        const int n = size * (k ? 4 : 1);
        nlohmann::json render_doc = doc;
        if (k == 0) render_doc["style"].update(style_override);
        const fs::path scene_copy =
            dir / (scene_name + "_" + preset + "_" + std::to_string(n) + ".json");
        std::ofstream(scene_copy) << render_doc.dump(2);
        const fs::path out = dir / (scene_name + "_" + preset + "_" + std::to_string(n));
        const std::string frames = std::to_string(frame) + ":" + std::to_string(frame + 1);
        if (!run_quiet(wisp + " render " + scene_copy.string() + " --anim " + anim + " --size " +
                       std::to_string(n) + "x" + std::to_string(n) + " --frames " + frames +
                       " -q -o " + out.string())) {
          std::fprintf(stderr, "wisp-bench quality: rendering %s failed\n", out.c_str());
          return 1;
        }
        char name[32];
        std::snprintf(name, sizeof name, "frame_%04d.png", frame);
        png[k] = out / name;
      }
      const auto bg = doc.value("render", nlohmann::json::object())
                          .value("background_color", std::vector<float>{0.93f, 0.91f, 0.87f});
      const render::FrameQuality q =
          render::frame_quality(png[0], png[1], Eigen::Vector3f(bg[0], bg[1], bg[2]));
      results.push_back({{"scene", scene_name},
                         {"preset", preset},
                         {"figure_pixels", q.figure_pixels},
                         {"p99", q.p99},
                         {"percent_over_32", 100 * q.over_32},
                         {"mean", q.mean},
                         {"meets_bar", q.p99 <= 12 && q.over_32 <= 0.003}});
    }
  }
  const nlohmann::json out = {{"benchmark", "quality"},
                              {"frame", frame},
                              {"size", size},
                              {"reference_size", 4 * size},
                              {"style_at_1_1", style_override},
                              {"bar", {{"p99", 12}, {"percent_over_32", 0.3}}},
                              {"results", results}};
  std::printf("%s\n", out.dump(2).c_str());
  fs::remove_all(dir);
  return 0;
}

}  // namespace wisp::bench
