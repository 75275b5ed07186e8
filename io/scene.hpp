// The scene file (JSON): one object with a part per concern: the physical parts `head`, `hair`,
// `fur`, `motion`, `sim` and `camera`, and the look: `style` (vector::HairStyle), `light` and
// `render` (docs/scene.md lists every field, its default and unit). Every field is optional;
// unknown fields, wrong types and out-of-range values are errors naming the file and the field
// ("scene.json: hair.cuont: unknown field (did you mean \"count\"?)").
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "sim/body.hpp"
#include "sim/camera.hpp"
#include "sim/fur.hpp"
#include "sim/params.hpp"
#include "sim/simulate.hpp"
#include "vector/hair_style.hpp"

namespace wisp::io {

// How frames are rendered and what is written besides them (the scene's `render` part).
// Colours are RGB in [0,1], in the same space as the style's colours.
struct RenderParams {
  Eigen::Vector3f background_color{0.93f, 0.91f, 0.87f};
  Eigen::Vector3f skin_color{0.96f, 0.80f, 0.69f};  // head and body (shaded by the light)
  bool body = true;   // draw the head (and neck and torso) under the hair
  bool torso = true;  // with `body`: also the neck, torso and upper arms
  bool face = true;   // with `body`: facial features on the head
  Eigen::Vector3f face_color{0.36f, 0.22f, 0.18f};  // their ink
  double solver_tolerance = 1e-4;  // diffusion solve: relative residual per channel
  int warm_start_block = 8;        // frames solved in sequence, each warm-started by the previous
  bool video = true;               // write preview.mp4
  int contact_sheet_columns = 6;   // tiles per row of contact.png
  bool antialias = true;           // mix both sides' colours where sharp curves cross pixels
};

// Throws std::invalid_argument("field: what") for a field out of range (see sim/params.hpp).
void validate(const RenderParams& render);

struct Scene {
  std::filesystem::path path;  // the scene file; relative file names inside resolve from its folder
  sim::HeadParams head;
  sim::HairParams hair;
  sim::FurParams fur;  // short dense hair on the head (sim/fur.hpp); none by default
  sim::MotionParams motion;
  sim::SimParams sim;
  sim::CameraParams camera;
  vector::HairStyle style;
  Eigen::Vector3d light_dir = sim::default_light_dir();  // unit, world, towards the light
  RenderParams render;
};

// Reads and validates a scene file. Throws std::invalid_argument / std::runtime_error with a
// one-line message naming the file and the field.
Scene load_scene(const std::filesystem::path& path);

// Validates an already parsed document; `path` names it in messages and anchors relative files.
Scene parse_scene(const nlohmann::json& doc, const std::filesystem::path& path);

}  // namespace wisp::io
