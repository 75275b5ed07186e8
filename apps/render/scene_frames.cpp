// Scene -> projected frames and bodies (see scene_frames.hpp).
#include "apps/render/scene_frames.hpp"
#include "apps/render/scene_setup.hpp"

#include "apps/render/body_occluders.hpp"

#include <cmath>
#include <functional>
#include <memory>
#include <optional>
#include <regex>
#include <stdexcept>

#include "io/anim_file.hpp"
#include "io/drawing_xml.hpp"
#include "sim/camera.hpp"
#include "sim/simulate.hpp"
#include "sim/solver.hpp"

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
  std::optional<sim::SimSetup> setup;
  if (options.anim.empty() || scene.fur.count > 0) setup = load_sim_setup(scene);
  if (!options.anim.empty()) {
    out.anim = io::read_animation(options.anim);
  } else {
    out.anim = sim::simulate(*setup, options.sim_progress);
  }
  if (scene.fur.count > 0) {
    out.fur = std::make_shared<const sim::FurModel>(
        sim::make_fur(scene.fur, sim::HeadShape(out.anim.head)));
    std::vector<double> times;
    for (const sim::StrandFrame& f : out.anim.frames) times.push_back(f.time);
    out.fur_motion = sim::simulate_fur(*out.fur, scene.fur, sim::Environment(*setup), times);
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
    // The base coat lies under the hair and the fur alike.
    std::vector<Eigen::Vector3d> roots = sim::local_roots(out.anim.frames.front());
    if (out.fur)
      for (const sim::FurTuftRest& t : out.fur->tufts) roots.push_back(t.root);
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
  // Frames are 8-bit: the solve stops within a quarter step of the exact discrete answer
  // (which replaces the residual tolerance as the stopping rule).
  setup.solver.max_error = diffusion::kEightBitError;
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

std::vector<vector::FurTuft> frame_fur(const SceneFrames& frames, int k) {
  if (!frames.fur) return {};
  const io::Scene& scene = frames.scene;
  const vector::FurStyle& style = scene.style.fur;
  // Tufts beyond the fin band are transparent unless the style lays them over the front.
  const double max_facing = style.interior_opacity > 0 ? 1.0 : style.fin_band;
  const sim::ProjectedFur fur =
      sim::project_fur(*frames.fur, frames.fur_motion.tips.at(k), frames.anim.frames.at(k).head,
                       sim::Camera::look_at(scene.camera), scene.light_dir, max_facing);
  return vector::fur_tufts(fur, scene.style);
}

BodyLayer frame_body(const SceneFrames& frames, int k) {
  BodyLayer layer;
  layer.fur = frame_fur(frames, k);
  if (!frames.body) return layer;
  const io::Scene& scene = frames.scene;
  const sim::HeadPose& pose = frames.anim.frames.at(k).head;
  const sim::Camera camera = sim::Camera::look_at(scene.camera);
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

namespace {

// The fur's coat seen through a pixel: the lit colour (vector::coat_color) of the head point
// there, with the fur's combed direction; off the head (the base's outline runs along the
// silhouette), the head's point nearest the eye ray.
std::function<Eigen::Vector3f(const Eigen::Vector2d&)> coat_shade(
    const SceneFrames& frames, const sim::HeadPose& pose, const sim::Camera& camera,
    std::shared_ptr<const sim::ScalpView> view) {
  const sim::HeadShape& head = frames.head->head();
  const Eigen::Vector3d centre = pose.to_world(head.center());
  return [&frames, &head, pose, camera, centre, view](const Eigen::Vector2d& p) {
    const Eigen::Vector3d ray =
        (camera.focal_px * camera.forward + (p.x() - 0.5 * camera.width) * camera.right -
         (p.y() - 0.5 * camera.height) * camera.up)
            .normalized();
    const double depth = view->depth(p);
    Eigen::Vector3d local;
    if (std::isfinite(depth)) {
      local = pose.to_local(camera.eye + depth * ray);
    } else {
      const Eigen::Vector3d nearest = camera.eye + (centre - camera.eye).dot(ray) * ray;
      local = head.surface_point(pose.to_local(nearest) - head.center());
    }
    Eigen::Vector3d n;
    head.distance(local, &n);
    n.normalize();
    const Eigen::Vector3d T = pose.rotation * sim::fur_direction(n, frames.scene.fur);
    return vector::coat_color(T, pose.rotation * n, frames.scene.light_dir, frames.scene.style);
  };
}

}  // namespace

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
  vector::HairBase base = vector::trace_hair_base(
      [&](const Eigen::Vector2d& p) { return view->field(p); },
      [view](const Eigen::Vector2d& p) { return view->depth(p); }, box, options);
  if (frames.fur) base.shade = coat_shade(frames, pose, camera, view);
  return base;
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
