// wisp-bench fronts: how right the arrangement's fronts are where hair meets the head and body.
// For the default and curly scenes, frame 40 at 512^2 and 2048^2 (`wisp-bench fronts [SIZE...]`),
// random points are thrown in every covered face inside the view, more than 1e-3 px inside it,
// and at each the depths there decide: the nearest of the face's covering wisps (band_depth)
// against the occluders whose rings hold the point (their ray cast). Where that is not the
// face's front (a wisp, or none for an occluder), the point counts as wrong, and the face's area
// times its share of wrong points as wrong area. The same frame's arrangement is built three
// ways in the same run: as rendered, without the occluder seams, and without those and the cut
// of hidden cells (vector/arrangement.hpp). Between wisps the depth seams make every point right
// (tests/vector/test_depth_seams.cpp); what this measures is the hair's edge against the body.
#include <unistd.h>

#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "apps/render/render_pipeline.hpp"
#include "apps/render/scene_frames.hpp"
#include "bench/benches.hpp"
#include "vector/band_depth.hpp"

namespace wisp::bench {
namespace {

namespace fs = std::filesystem;
using Eigen::Vector2d;

// Whether p is inside the rings (even-odd), and its distance to their nearest edge.
std::pair<bool, double> locate(const std::vector<const std::vector<Vector2d>*>& rings,
                               const Vector2d& p) {
  bool in = false;
  double margin = INFINITY;
  for (const auto* ring : rings)
    for (size_t i = 0, j = ring->size() - 1; i < ring->size(); j = i++) {
      const Vector2d &a = (*ring)[j], &b = (*ring)[i];
      if ((a.y() > p.y()) != (b.y() > p.y()) &&
          p.x() < a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y()))
        in = !in;
      const Vector2d ab = b - a;
      const double l = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
      margin = std::min(margin, (a + l * ab - p).norm());
    }
  return {in, margin};
}

double ring_area(const std::vector<Vector2d>& r) {
  double a = 0;
  for (size_t i = 0, j = r.size() - 1; i < r.size(); j = i++)
    a += r[j].x() * r[i].y() - r[i].x() * r[j].y();
  return 0.5 * std::abs(a);
}

struct Wrong {
  long faces = 0, points = 0, wrong_points = 0, wrong_faces = 0;
  double area = 0, wrong_area = 0;  // px^2
};

Wrong check(const std::vector<vector::Wisp>& wisps, const vector::ArrangementView& view,
            const std::vector<vector::Occluder>& occluders) {
  Wrong c;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0, 1);
  for (const vector::ViewFace& f : view.faces) {
    if (f.cover.empty() || f.outer.empty() || !f.in_view) continue;
    std::vector<const std::vector<Vector2d>*> rings = {&f.outer};
    Eigen::AlignedBox2d box;
    for (const Vector2d& p : f.outer) box.extend(p);
    double area = ring_area(f.outer);
    for (const auto& h : f.holes) rings.push_back(&h), area -= ring_area(h);
    ++c.faces;
    c.area += area;
    int tried = 0, wrong = 0;
    for (int k = 0; k < 16; ++k) {
      const Vector2d p = box.min() + Vector2d(unit(rng), unit(rng)).cwiseProduct(box.sizes());
      const auto [in, margin] = locate(rings, p);
      if (!in || margin < 1e-3) continue;
      double best = INFINITY;
      int nearest = -1;
      for (const auto& [w, winding] : f.cover)
        if (const double z = vector::band_depth(wisps[w], p).depth; z < best) best = z, nearest = w;
      double occluder = INFINITY;
      for (const vector::Occluder& o : occluders)
        if (locate({&o.ring}, p).first) occluder = std::min(occluder, o.depth(p));
      if (std::abs(occluder - best) < 1e-9 * best) continue;  // a tie either way
      ++tried;
      wrong += (occluder < best ? -1 : nearest) != f.front;
    }
    c.points += tried, c.wrong_points += wrong, c.wrong_faces += wrong > 0;
    if (tried > 0) c.wrong_area += area * wrong / tried;
  }
  return c;
}

nlohmann::json to_json(const Wrong& c) {
  return {{"faces", c.faces},
          {"points", c.points},
          {"wrong_points", c.wrong_points},
          {"wrong_faces", c.wrong_faces},
          {"covered_px2", c.area},
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
        row[way.name] = to_json(check(r.wisps, a.view, arr.occluders));
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
