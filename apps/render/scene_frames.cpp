// Scene -> projected frames and bodies (see scene_frames.hpp).
#include "apps/render/scene_frames.hpp"
#include "apps/render/scene_setup.hpp"

#include "apps/render/body_occluders.hpp"

#include <cmath>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>

#include "io/anim_file.hpp"
#include "sim/camera.hpp"
#include "sim/simulate.hpp"
#include "sim/solver.hpp"

namespace wisp::render {

namespace {

// Thrown by FrameFeed::publish, or after the last frame wanted, to end the feed's thread early.
struct FeedStopped {};

void apply_size(io::Scene& scene, const SceneFramesOptions& options) {
  if (options.width > 0 && options.height > 0) {
    scene.camera.width = options.width;
    scene.camera.height = options.height;
  }
}

// The projector of the frames, in order: each frame's head occlusion starts from the previous
// frame's (hysteresis).
std::unique_ptr<sim::Projector> make_projector(const SceneFrames& out) {
  sim::ProjectorOptions projection = projector_options(out.scene);
  projection.widths = out.anim.widths;
  return std::make_unique<sim::Projector>(out.anim.head, out.scene.camera, projection);
}

// The body the scene draws, from the head alone.
void add_body(SceneFrames& out) {
  const sim::BodyParams body = body_params(out.scene);
  if (body.head || body.neck || body.torso)
    out.body = std::make_shared<const sim::BodyModel>(out.anim.head, body);
}

// The hair base's scalp, from frame 0's roots (and the fur's), once frame 0 is there.
void add_scalp(SceneFrames& out) {
  const vector::BaseStyle& base = out.scene.style.base;
  if (!base.enabled || out.anim.frames.empty()) return;
  // The base coat lies under the hair and the fur alike.
  std::vector<Eigen::Vector3d> roots = sim::local_roots(out.anim.frames.front());
  if (out.fur)
    for (const sim::FurTuftRest& t : out.fur->tufts) roots.push_back(t.root);
  if (roots.empty()) return;
  out.scalp = std::make_shared<const sim::Scalp>(std::move(roots), base.spread);
  // Any body model tessellates the head; a scene that draws no body still gets one.
  out.head = out.body
                 ? out.body
                 : std::make_shared<const sim::BodyModel>(out.anim.head, body_params(out.scene));
}

}  // namespace

FrameFeed::~FrameFeed() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  if (thread_.joinable()) thread_.join();
}

void FrameFeed::start(std::function<void(FrameFeed&)> make) {
  start_ = diffusion::Clock::now();
  thread_ = std::thread([this, make = std::move(make)] {
    std::exception_ptr error;
    try {
      make(*this);
    } catch (const FeedStopped&) {
    } catch (...) {
      error = std::current_exception();
    }
    std::lock_guard<std::mutex> lock(mutex_);
    error_ = error;
    done_ = true;
    ms_ = diffusion::ms_since(start_);
    changed_.notify_all();
  });
}

void FrameFeed::publish(int ready) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (stopping_) throw FeedStopped{};
  ready_ = ready;
  changed_.notify_all();
}

void FrameFeed::wait_for(int k) {
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, [&] { return ready_ > k || done_; });
  if (ready_ > k) return;
  if (error_) std::rethrow_exception(error_);
  throw std::logic_error("frame " + std::to_string(k) + " of " + std::to_string(count_) +
                         " was never made");
}

double FrameFeed::ms() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return done_ ? ms_ : diffusion::ms_since(start_);
}

SceneFrames load_scene_frames(const std::filesystem::path& scene_path,
                              const SceneFramesOptions& options) {
  return load_scene_frames(io::load_scene(scene_path), options);
}

SceneFrames load_scene_frames(io::Scene scene_in, const SceneFramesOptions& options) {
  SceneFrames out;
  out.scene = std::move(scene_in);
  io::Scene& scene = out.scene;
  apply_size(scene, options);
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
  const std::unique_ptr<sim::Projector> projector = make_projector(out);
  out.projected.reserve(out.anim.frames.size());
  for (const sim::StrandFrame& f : out.anim.frames) out.projected.push_back(projector->project(f));
  add_body(out);
  add_scalp(out);
  return out;
}

std::unique_ptr<SceneFrames> stream_scene_frames(io::Scene scene,
                                                 const SceneFramesOptions& options) {
  if (scene.fur.count > 0)
    return std::make_unique<SceneFrames>(load_scene_frames(std::move(scene), options));
  auto out = std::make_unique<SceneFrames>();
  out->scene = std::move(scene);
  apply_size(out->scene, options);
  // What the feed's thread works from; shared, since std::function wants a copyable callable.
  struct Source {
    std::optional<sim::SimSetup> setup;
    sim::Animation file;
    std::unique_ptr<sim::Projector> projector;
  };
  auto source = std::make_shared<Source>();
  int count = 0;
  if (options.anim.empty()) {
    source->setup = load_sim_setup(out->scene);
    const sim::SimSetup& setup = *source->setup;
    out->anim.fps = setup.sim.fps;  // as sim::simulate sets them
    out->anim.head = setup.head;
    out->anim.widths = setup.widths;
    count = sim::animation_frame_count(setup);
  } else {
    source->file = io::read_animation(options.anim);
    out->anim.fps = source->file.fps;
    out->anim.head = source->file.head;
    out->anim.widths = source->file.widths;
    count = int(source->file.frames.size());
  }
  out->anim.frames.resize(count);
  out->projected.resize(count);
  source->projector = make_projector(*out);  // a bad camera is refused here, not by a wait
  add_body(*out);
  // The frames made: up to the last one wanted, and frame 1 with frame 0 (its motion neighbour).
  const int made = options.needed > 0 ? std::min(count, std::max(options.needed, 2)) : count;
  out->feed = std::make_unique<FrameFeed>(count);
  // The slots are filled in order and published; the frames never move (out is on the heap)
  // and a frame is read only after its publication.
  SceneFrames* frames = out.get();
  out->feed->start([frames, source, made](FrameFeed& feed) {
    int k = 0;
    const auto take = [&](sim::StrandFrame f) {
      if (k >= frames->frame_count()) throw std::logic_error("more frames than announced");
      frames->projected[k] = source->projector->project(f);
      frames->anim.frames[k] = std::move(f);
      if (k == 0) add_scalp(*frames);
      feed.publish(++k);
    };
    if (source->setup) {
      sim::simulate(*source->setup, {}, [&](const sim::StrandFrame& f) {
        take(f);
        if (k == made && made < frames->frame_count()) throw FeedStopped{};  // ends the simulation
      });
    } else {
      for (int i = 0; i < made && i < int(source->file.frames.size()); ++i)
        take(std::move(source->file.frames[i]));
    }
  });
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

std::shared_ptr<const sim::SurfaceRays> frame_head_rays(const SceneFrames& frames, int k) {
  const bool occluder = frames.body && frames.body->params().head;
  const bool base = frames.scalp && frames.head;
  if (!occluder && !base) return nullptr;
  // frames.head is frames.body when there is a body (add_scalp).
  const sim::BodyModel& model = occluder ? *frames.body : *frames.head;
  sim::BodySurface head = model.head_surface(frames.anim.frames.at(k).head);
  // With folds: the occluders' depth bound needs them (found when first asked for).
  return std::make_shared<const sim::SurfaceRays>(
      std::move(head.vertices), std::move(head.triangles),
      sim::Camera::look_at(frames.scene.camera), true, head.neighbours);
}

std::vector<vector::Occluder> frame_occluders(const SceneFrames& frames, int k,
                                              std::shared_ptr<const sim::SurfaceRays> head) {
  if (!frames.body) return {};
  return body_occluders(*frames.body, frames.anim.frames.at(k).head,
                        sim::Camera::look_at(frames.scene.camera),
                        frames.scene.style.geometry.width, std::move(head));
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

vector::HairBase frame_base(const SceneFrames& frames, int k,
                            std::shared_ptr<const sim::SurfaceRays> head) {
  if (!frames.scalp || !frames.head) return {};
  const io::Scene& scene = frames.scene;
  const sim::HeadPose& pose = frames.anim.frames.at(k).head;
  const sim::Camera camera = sim::Camera::look_at(scene.camera);
  if (!head) head = frame_head_rays(frames, k);
  auto view = std::make_shared<const sim::ScalpView>(frames.scalp, pose, std::move(head),
                                                     scene.style.base.level);
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

}  // namespace wisp::render
