// wisp-bench groom: dense grooms to guides (sim/clumps.hpp). Generates the procedural hair at
// N strands of P points, writes it as a .hair file and times what `wisp render` does with it
// before simulating a scene with hair.guides: read the file, cluster its strands, measure the
// clump widths (render::load_sim_setup); best and median of R runs. With --figure DIR it keeps
// DIR/groom.hair and DIR/scene.json and writes DIR/figure.json (every strand and the clumps'
// wisps at rest, projected by the scene's camera, with each strand's clump) for
// scripts/groom-figure.
// Usage: wisp-bench groom [--strands N] [--points P] [--guides K] [--runs R] [--figure DIR]
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "apps/render/scene_setup.hpp"
#include "bench/benches.hpp"
#include "diffusion/timer.hpp"
#include "io/hair_file.hpp"
#include "sim/camera.hpp"
#include "sim/clumps.hpp"
#include "vector/wisp.hpp"

namespace wisp::bench {
namespace {

// The default scene's camera and head, the hair at rest (no motion).
nlohmann::json scene_json(int guides) {
  return {{"head", {{"shoulders", true}}},
          {"hair", {{"source", "hair"}, {"file", "groom.hair"}, {"guides", guides}}},
          {"motion", {{"preset", "none"}, {"duration", 0.1}}},
          {"camera",
           {{"eye", {0.68, 0.04, 0.86}},
            {"target", {0.0, -0.08, 0.0}},
            {"width", 384},
            {"height", 384}}},
          {"render", {{"video", false}}}};
}

// Visible runs of projected samples, as flat [x0, y0, x1, y1, ...] arrays rounded to 0.1 px.
void add_runs(const sim::ProjectedStrand& s, int clump, nlohmann::json& lines,
              nlohmann::json& clumps) {
  nlohmann::json run = nlohmann::json::array();
  const auto flush = [&] {
    if (run.size() >= 4) {
      lines.push_back(run);
      clumps.push_back(clump);
    }
    run = nlohmann::json::array();
  };
  for (std::size_t i = 0; i < s.pixel.size(); ++i) {
    if (!s.visible[i]) {
      flush();
      continue;
    }
    run.push_back(std::round(s.pixel[i].x() * 10) / 10);
    run.push_back(std::round(s.pixel[i].y() * 10) / 10);
  }
  flush();
}

void write_figure(const std::filesystem::path& dir, const std::vector<sim::Polyline>& strands,
                  const io::Scene& scene) {
  sim::ClumpOptions options;
  options.count = scene.hair.guides;
  options.seed = scene.hair.seed;
  const sim::Clumps clumps = sim::cluster_strands(strands, options);
  const sim::SimSetup setup = render::load_sim_setup(scene);
  const sim::HeadGeometry& head = setup.head;

  nlohmann::json fig = {{"width", scene.camera.width},
                        {"height", scene.camera.height},
                        {"strands", nlohmann::json::array()},
                        {"strand_clump", nlohmann::json::array()},
                        {"wisps", nlohmann::json::array()}};
  sim::Projector all(head, scene.camera);
  sim::StrandFrame rest;
  rest.strands = strands;
  const sim::ProjectedFrame dense = all.project(rest);
  for (std::size_t i = 0; i < strands.size(); ++i)
    add_runs(dense.strands[i], clumps.clump_of[i], fig["strands"], fig["strand_clump"]);

  sim::ProjectorOptions projection;
  projection.widths = setup.widths;
  sim::Projector guides(head, scene.camera, projection);
  rest.strands = setup.rest;
  const sim::ProjectedFrame frame = guides.project(rest);
  const vector::WispStyle style = scene.style.geometry;
  for (const sim::ProjectedStrand& s : frame.strands) {
    const std::optional<vector::Wisp> w = vector::build_wisp(s, frame.focal_px, style);
    nlohmann::json outline = nlohmann::json::array();
    if (w)
      for (const vector::OutlineVertex& v : vector::outline_polygon(*w)) {
        outline.push_back(std::round(v.p.x() * 10) / 10);
        outline.push_back(std::round(v.p.y() * 10) / 10);
      }
    fig["wisps"].push_back(outline);
  }
  std::ofstream(dir / "figure.json") << fig.dump();
}

}  // namespace

int run_groom(const std::vector<std::string>& args) {
  int strands = 20000, points = 30, guides = 150, runs = 5;
  std::filesystem::path figure;
  for (std::size_t i = 0; i + 1 < args.size(); i += 2) {
    if (args[i] == "--strands") strands = std::stoi(args[i + 1]);
    if (args[i] == "--points") points = std::stoi(args[i + 1]);
    if (args[i] == "--guides") guides = std::stoi(args[i + 1]);
    if (args[i] == "--runs") runs = std::max(1, std::stoi(args[i + 1]));
    if (args[i] == "--figure") figure = args[i + 1];
  }
  const std::filesystem::path dir =
      figure.empty() ? std::filesystem::temp_directory_path() / "wisp-bench-groom" : figure;
  std::filesystem::create_directories(dir);

  sim::HairParams groom;
  groom.count = strands;
  groom.segments = points - 1;
  std::fprintf(stderr, "groom: generating %d strands of %d points...\n", strands, points);
  io::HairFile hair;
  hair.strands = sim::generate_hair(groom, sim::HeadShape(sim::HeadGeometry{}));
  io::write_hair_file(dir / "groom.hair", hair);
  std::ofstream(dir / "scene.json") << scene_json(guides).dump(2);
  const io::Scene scene = io::load_scene(dir / "scene.json");

  std::vector<double> times;
  for (int r = 0; r < runs; ++r) {
    const auto start = diffusion::Clock::now();
    const sim::SimSetup setup = render::load_sim_setup(scene);
    times.push_back(diffusion::seconds_since(start));
    std::fprintf(stderr, "groom: run %d: %.3f s, %zu guides\n", r + 1, times.back(),
                 setup.rest.size());
  }
  std::sort(times.begin(), times.end());
  std::printf(
      "{\"bench\": \"groom\", \"strands\": %d, \"points\": %d, \"guides\": %d, \"runs\": %d, "
      "\"load_and_cluster_s\": {\"best\": %.3f, \"median\": %.3f, \"worst\": %.3f}}\n",
      strands, points, guides, runs, times.front(), times[times.size() / 2], times.back());
  if (!figure.empty()) {
    write_figure(dir, io::read_hair_file(dir / "groom.hair").strands, scene);
  } else {
    std::filesystem::remove_all(dir);
  }
  return 0;
}

}  // namespace wisp::bench
