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
  sim::ProjectorOptions projection = projector_options(scene);
  projection.widths = out.anim.widths;
  sim::Projector projector(out.anim.head, scene.camera, projection);
  out.projected.reserve(out.anim.frames.size());
  for (const sim::StrandFrame& f : out.anim.frames) out.projected.push_back(projector.project(f));

  const sim::BodyParams body = body_params(scene);
  if (body.head || body.neck || body.torso)
    out.body = std::make_shared<const sim::BodyModel>(out.anim.head, body);
  const vector::BaseStyle& base = scene.style.base;
  if (base.enabled && !out.anim.frames.empty()) {
    std::vector<Eigen::Vector3d> roots = sim::local_roots(out.anim.frames.front());
    if (!roots.empty()) {
      out.scalp = std::make_shared<const sim::Scalp>(std::move(roots), base.spread);
      // Any body model tessellates the head; a scene that draws no body still gets one.
      out.head = out.body ? out.body : std::make_shared<const sim::BodyModel>(out.anim.head, body);
    }
  }
  return out;
}

FrameSetup frame_setup(const io::Scene& scene) {
  FrameSetup setup;
  setup.style = scene.style;
  setup.solver.tolerance = scene.render.solver_tolerance;
  setup.background = scene.render.background_color;
  setup.antialias = scene.render.antialias;
  const sim::CameraParams& camera = scene.camera;
  setup.lens.aperture = camera.aperture;
  setup.lens.focus_distance =
      camera.focus_distance > 0 ? camera.focus_distance : (camera.target - camera.eye).norm();
  return setup;
}

BodyTones body_tones(const io::Scene& scene) {
  BodyTones tones;
  tones.lit = scene.render.skin_color;
  tones.shadow = tones.lit * 0.72f;
  return tones;
}

BodyLayer frame_body(const SceneFrames& frames, int k) {
  if (!frames.body) return {};
  const io::Scene& scene = frames.scene;
  const sim::HeadPose& pose = frames.anim.frames.at(k).head;
  const sim::Camera camera = sim::Camera::look_at(scene.camera);
  BodyLayer layer;
  layer.projected = frames.body->project(pose, camera, scene.light_dir);
  layer.paths = body_paths(layer.projected, body_tones(scene));
  layer.face = face_strokes(frames.body->face(pose, camera), scene.render.face_color);
  return layer;
}

std::vector<vector::Occluder> frame_occluders(const SceneFrames& frames, int k) {
  if (!frames.body) return {};
  return body_occluders(*frames.body, frames.anim.frames.at(k).head,
                        sim::Camera::look_at(frames.scene.camera),
                        frames.scene.style.geometry.width);
}

vector::HairBase frame_base(const SceneFrames& frames, int k) {
  if (!frames.scalp || !frames.head) return {};
  const io::Scene& scene = frames.scene;
  const sim::HeadPose& pose = frames.anim.frames.at(k).head;
  const sim::Camera camera = sim::Camera::look_at(scene.camera);
  auto view = std::make_shared<const sim::ScalpView>(
      frames.scalp, pose, frames.head->head_triangles(pose), camera, scene.style.base.level);
  // The head's box within the frame; the tracer pads it, so a scalp running past the frame is
  // cut outside it.
  Eigen::AlignedBox2d box = view->box();
  box = box.intersection(vector::image_rect(camera.width, camera.height));
  if (box.isEmpty()) return {};
  vector::HairBaseOptions options;
  options.cell_px = std::max(1.0, std::min(camera.width, camera.height) / 512.0);
  return vector::trace_hair_base([&](const Eigen::Vector2d& p) { return view->field(p); },
                                 [view](const Eigen::Vector2d& p) { return view->depth(p); }, box,
                                 options);
}

const sim::ProjectedFrame* motion_neighbour(const SceneFrames& frames, int k) {
  const int other = k > 0 ? k - 1 : k + 1;
  return other < frames.frame_count() ? &frames.projected[other] : nullptr;
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
