// stats.json of `wisp render` (see render_stats.hpp).
#include "apps/render/render_stats.hpp"

#include <algorithm>
#include <map>

namespace wisp::render {
namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

}  // namespace

nlohmann::json frame_stats(const SceneFrames& frames, int k, const FrameResult& r, double write_ms,
                           double frame_ms) {
  return {{"frame", k},
          {"time", frames.anim.frames[k].time},
          {"strands", frames.projected[k].strands.size()},
          {"wisps", r.wisps.size()},
          {"fur_tufts", r.picture.fur.size()},
          {"visible_curves", r.curves.size()},
          {"curve_kinds",
           {{"outlines", r.curve_stats.outlines},
            {"centre_lines", r.curve_stats.centre_lines},
            {"band_edges", r.curve_stats.band_edges},
            {"highlights", r.curve_stats.highlights},
            {"base", r.base_curves}}},
          {"ink_strokes", r.picture.ink.size()},
          {"hatch_strokes", {{"hair", r.hatching.size()}, {"body", r.body_hatching.size()}}},
          {"faces", r.arrangement.stats.faces},
          {"edges", r.arrangement.stats.edges},
          {"intersections", r.arrangement.stats.intersections},
          {"hidden_wisps", r.arrangement.stats.hidden_wisps},
          {"hidden_segments", r.arrangement.stats.hidden_segments},
          {"cuts", r.arrangement.stats.cuts},
          {"seam_segments", r.arrangement.stats.seam_segments},
          {"solve_window", {r.window.x, r.window.y, r.window.width, r.window.height}},
          {"solver_cycles", r.solve.cycles},
          {"solver_residual", r.solve.final_residual},
          {"solver_converged", r.solve.converged || r.window.pixel_count() == 0},
          {"antialiased_pixels", r.antialias.pixels},
          {"ms",
           {{"body", r.time.body},
            {"wisps", r.time.wisps},
            {"arrangement", r.time.arrangement},
            {"arrangement_sweep", r.arrangement.stats.sweep_ms},
            {"arrangement_cull", r.arrangement.stats.cull_ms},
            {"arrangement_seams", r.arrangement.stats.seams_ms},
            {"arrangement_resolve", r.arrangement.stats.resolve_ms},
            {"curves", r.time.curves},
            {"ink", r.time.ink},
            {"hatching", r.time.hatching},
            {"rasterize", r.time.rasterize},
            {"solve", r.time.solve},
            {"solve_setup", r.solve.setup_ms},
            {"antialias", r.time.antialias},
            {"blur", r.time.blur},
            {"write", write_ms},
            {"frame", frame_ms}}}};
}

nlohmann::json run_stats(const std::string& scene_file, const io::Scene& scene,
                         int frames_in_animation, FrameRange range,
                         const std::vector<nlohmann::json>& records, int rendered,
                         const RunTimes& ms) {
  std::map<std::string, std::vector<double>> stage;
  for (const nlohmann::json& f : records)
    for (const auto& [name, t] : f["ms"].items()) stage[name].push_back(t.get<double>());
  nlohmann::json medians, totals;
  for (const auto& [name, v] : stage) {
    medians[name] = median(v);
    double sum = 0;
    for (double x : v) sum += x;
    totals[name] = sum;
  }
  return {{"scene", scene_file},
          {"frames_in_animation", frames_in_animation},
          {"range", {range.first, range.last}},
          {"rendered", rendered},
          {"skipped", range.size() - rendered},
          {"width", scene.camera.width},
          {"height", scene.camera.height},
          {"ms",
           {{"simulate_and_project", ms.simulate_and_project},
            {"frames", ms.frames},
            {"first_frame", ms.first_frame},
            {"video_and_contact_sheet", ms.video_and_contact_sheet},
            {"animated_svg", ms.animated_svg},
            {"total", ms.total}}},
          {"frames_per_second", ms.frames > 0 ? rendered * 1000.0 / ms.frames : 0.0},
          {"stage_ms_median", medians},
          {"stage_ms_total", totals},
          {"frames", records}};
}

nlohmann::json merged_stats(const std::vector<RunStatsFile>& runs, const std::string& scene_file,
                            io::Scene scene, int frames_in_animation, FrameRange range,
                            double previews_ms, const std::vector<nlohmann::json>& kept) {
  std::map<int, nlohmann::json> by_frame;
  for (const nlohmann::json& f : kept) {
    const int k = f.value("frame", -1);
    if (k >= range.first && k < range.last) by_frame[k] = f;
  }
  RunTimes ms;
  nlohmann::json listed = nlohmann::json::array();
  for (const RunStatsFile& run : runs) {
    const nlohmann::json& s = run.stats;
    for (const nlohmann::json& f : s.value("frames", nlohmann::json::array())) {
      const int k = f.value("frame", -1);
      if (k >= range.first && k < range.last) by_frame[k] = f;
    }
    const nlohmann::json times = s.value("ms", nlohmann::json::object());
    ms.simulate_and_project += times.value("simulate_and_project", 0.0);
    ms.frames += times.value("frames", 0.0);
    ms.total += times.value("total", 0.0);
    scene.camera.width = s.value("width", scene.camera.width);
    scene.camera.height = s.value("height", scene.camera.height);
    listed.push_back({{"file", run.file},
                      {"range", s.value("range", nlohmann::json::array())},
                      {"rendered", s.value("rendered", 0)},
                      {"ms_total", times.value("total", 0.0)}});
  }
  std::vector<nlohmann::json> written;
  for (auto& [k, f] : by_frame) written.push_back(std::move(f));
  ms.video_and_contact_sheet = previews_ms;
  ms.total += previews_ms;
  nlohmann::json merged =
      run_stats(scene_file, scene, frames_in_animation, range, written, int(written.size()), ms);
  merged["runs"] = listed;
  return merged;
}

}  // namespace wisp::render
