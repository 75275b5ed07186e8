// Scene -> projected frames and bodies (see scene_frames.hpp).
#include "apps/render/scene_frames.hpp"
#include "apps/render/scene_setup.hpp"

#include "apps/render/body_occluders.hpp"

#include <regex>
#include <stdexcept>

#include "io/anim_file.hpp"
#include "io/drawing_xml.hpp"
#include "sim/camera.hpp"
#include "sim/simulate.hpp"

namespace wisp::render {

SceneFrames load_scene_frames(const std::filesystem::path& scene_path,
                              const SceneFramesOptions& options) {
  return load_scene_frames(io::load_scene(scene_path), options);
}

SceneFrames load_scene_frames(io::Scene scene_in, const SceneFramesOptions& options) {
  SceneFrames out;
  out.scene = std::move(scene_in);
  io::Scene& scene = out.scene;
  if (options.width > 0 && options.height > 0) {
    scene.camera.width = options.width;
    scene.camera.height = options.height;
  }
  if (!options.anim.empty()) {
    out.anim = io::read_animation(options.anim);
  } else {
    const sim::SimSetup setup = load_sim_setup(scene);
    out.anim = sim::simulate(setup, options.sim_progress);
  }

  // In order: each frame's head occlusion starts from the previous frame's (hysteresis).
  sim::Projector projector(out.anim.head, scene.camera, projector_options(scene));
  out.projected.reserve(out.anim.frames.size());
  for (const sim::StrandFrame& f : out.anim.frames) out.projected.push_back(projector.project(f));

  const sim::BodyParams body = body_params(scene);
  if (body.head || body.neck || body.torso)
    out.body = std::make_shared<const sim::BodyModel>(out.anim.head, body);
  return out;
}

FrameSetup frame_setup(const io::Scene& scene) {
  FrameSetup setup;
  setup.style = scene.style;
  setup.solver.tolerance = scene.render.solver_tolerance;
  setup.background = scene.render.background_color;
  setup.antialias = scene.render.antialias;
  return setup;
}

std::vector<BodyPolygon> frame_body(const SceneFrames& frames, int k) {
  std::vector<BodyPolygon> out;
  if (!frames.body) return out;
  const io::Scene& scene = frames.scene;
  const sim::ProjectedBody body = frames.body->project(
      frames.anim.frames.at(k).head, sim::Camera::look_at(scene.camera), scene.light_dir);
  const Rgb lit = scene.render.skin_color, shadow = lit * 0.72f;
  constexpr double kBand = 0.45;  // half-Lambert shade where the shadow tone begins
  out.reserve(body.triangles.size());
  for (const sim::BodyTriangle& t : body.triangles) {
    // Split the triangle along the iso-line shade = kBand of its smooth (per-vertex) shading
    // into its lit and shadowed parts: the band edge runs smoothly across triangles.
    BodyPolygon bright{{}, lit}, dark{{}, shadow};
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector2d a = t.p[i], b = t.p[(i + 1) % 3];
      const double sa = t.vertex_shade[i], sb = t.vertex_shade[(i + 1) % 3];
      (sa >= kBand ? bright : dark).points.push_back(a);
      if ((sa >= kBand) != (sb >= kBand)) {
        const Eigen::Vector2d m = a + (b - a) * ((kBand - sa) / (sb - sa));
        bright.points.push_back(m);
        dark.points.push_back(m);
      }
    }
    for (BodyPolygon* part : {&dark, &bright})
      if (part->points.size() >= 3) out.push_back(std::move(*part));
  }
  return out;
}

std::vector<vector::Occluder> frame_occluders(const SceneFrames& frames, int k) {
  if (!frames.body) return {};
  return body_occluders(*frames.body, frames.anim.frames.at(k).head,
                        sim::Camera::look_at(frames.scene.camera),
                        frames.scene.style.geometry.width);
}

std::pair<int, int> parse_size(const std::string& option, const std::string& text) {
  std::smatch m;
  if (!std::regex_match(text, m, std::regex(R"((\d{1,6})x(\d{1,6}))")))
    throw std::invalid_argument(option + ": expected WxH, for example 512x512, got '" + text + "'");
  const int w = std::stoi(m[1]), h = std::stoi(m[2]);
  if (w < 1 || h < 1 || w > io::kMaxImageSide || h > io::kMaxImageSide)
    throw std::invalid_argument(option + " " + text + ": each side must be between 1 and " +
                                std::to_string(io::kMaxImageSide));
  return {w, h};
}

}  // namespace wisp::render
