// wisp-bench fronts: how right the arrangement's fronts are where hair meets the head and body.
// For the default and curly scenes, frame 40 at 512^2 and 2048^2 (`wisp-bench fronts [SIZE...]`),
// 16 random points a covered face are decided by the depths there and compared with the face's
// front (vector/front_check.hpp): the wrong points, and the faces' areas times their shares of
// wrong points. The same frame's arrangement is built three
// ways in the same run: as rendered, without the occluder seams, and without those and the cut
// of hidden cells (vector/arrangement.hpp). Between wisps the depth seams make every point right
// (tests/vector/test_depth_seams.cpp); what this measures is the hair's edge against the body.
#include <unistd.h>

#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "apps/render/render_pipeline.hpp"
#include "apps/render/scene_frames.hpp"
#include "bench/benches.hpp"
#include "vector/front_check.hpp"

namespace wisp::bench {
namespace {

namespace fs = std::filesystem;

nlohmann::json to_json(const vector::FrontCheck& c) {
  return {{"faces", c.faces},
          {"points", c.points},
          {"wrong_points", c.wrong_points},
          {"wrong_faces", c.wrong_faces},
          {"covered_px2", c.covered_area},
          {"wrong_px2", c.wrong_area}};
}

}  // namespace

int run_fronts(const std::vector<std::string>& args) {
  std::vector<int> sizes;
  for (const std::string& a : args) {
    int size = 0;
    const auto [end, error] = std::from_chars(a.data(), a.data() + a.size(), size);
    if (error != std::errc() || end != a.data() + a.size() || size < 16 || size > 4096) {
      std::fprintf(stderr, "wisp-bench fronts: size must be 16 to 4096, got '%s'\n", a.c_str());
      return 2;
    }
    sizes.push_back(size);
  }
  if (sizes.empty()) sizes = {512, 2048};
  const fs::path exe_dir = fs::canonical("/proc/self/exe").parent_path();
  const fs::path dir =
      fs::temp_directory_path() / ("wisp_bench_fronts_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const int frame = 40;
  nlohmann::json results = nlohmann::json::array();
  for (const std::string scene_name : {"default", "curly"}) {
    const std::string scene = std::string(WISP_SOURCE_DIR "/data/scenes/") + scene_name + ".json";
    const fs::path anim = dir / (scene_name + ".wsim");
    const std::string sim = (exe_dir / "wisp").string() + " simulate " + scene + " -o " +
                            anim.string() + " -q > /dev/null";
    if (std::system(sim.c_str()) != 0) {
      std::fprintf(stderr, "wisp-bench fronts: simulating %s failed\n", scene.c_str());
      return 1;
    }
    for (int size : sizes) {
      std::fprintf(stderr, "fronts bench: %s at %d^2\n", scene_name.c_str(), size);
      render::SceneFramesOptions options;
      options.anim = anim;
      options.width = options.height = size;
      const render::SceneFrames frames = render::load_scene_frames(scene, options);
      const render::FrameSetup setup = render::frame_setup(frames.scene);
      const render::FrameResult r = render::render_geometry(
          frames.projected.at(frame), {}, render::frame_occluders(frames, frame),
          render::frame_base(frames, frame), setup);
      nlohmann::json row = {{"scene", scene_name}, {"size", size}};
      struct Way {
        const char* name;
        bool cut, occluder_seams;
      };
      for (const Way& way : {Way{"rendered", true, true}, Way{"no_occluder_seams", true, false},
                             Way{"no_cut_no_occluder_seams", false, false}}) {
        vector::ArrangementOptions arr;
        arr.view = vector::image_rect(size, size);
        arr.keep_faces = true;
        arr.occluders = render::frame_occluders(frames, frame);
        arr.base = render::frame_base(frames, frame);
        arr.cut_hidden = way.cut;
        arr.occluder_seams = way.occluder_seams;
        const vector::WispArrangement a = vector::build_arrangement(r.wisps, arr);
        vector::FrontCheckOptions check;
        check.points_per_face = 16;
        row[way.name] = to_json(vector::check_fronts(r.wisps, a.view, arr.occluders, check));
        row[way.name]["arrangement_ms"] = a.stats.sweep_ms + a.stats.resolve_ms;
      }
      results.push_back(std::move(row));
    }
  }
  fs::remove_all(dir);
  const nlohmann::json out = {{"benchmark", "fronts"}, {"frame", frame}, {"results", results}};
  std::printf("%s\n", out.dump(2).c_str());
  return 0;
}

}  // namespace wisp::bench
