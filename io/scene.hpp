// The scene file (JSON): one object with a part per concern. This issue reads the physical parts,
// `head`, `hair`, `motion`, `sim` and `camera` (docs/scene.md lists every field, its default and
// unit); later parts (`style`, `light`, `render`) join the table in scene_json.cpp. Every field
// is optional; unknown fields, wrong types and out-of-range values are errors naming the file and
// the field ("scene.json: hair.cuont: unknown field (did you mean \"count\"?)").
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>

#include "sim/params.hpp"
#include "sim/simulate.hpp"

namespace wisp::io {

struct Scene {
  std::filesystem::path path;  // the scene file; relative file names inside resolve from its folder
  sim::HeadParams head;
  sim::HairParams hair;
  sim::MotionParams motion;
  sim::SimParams sim;
  sim::CameraParams camera;
};

// Reads and validates a scene file. Throws std::invalid_argument / std::runtime_error with a
// one-line message naming the file and the field.
Scene load_scene(const std::filesystem::path& path);

// Validates an already parsed document; `path` names it in messages and anchors relative files.
Scene parse_scene(const nlohmann::json& doc, const std::filesystem::path& path);

// Everything the simulator needs from a scene: reads the head mesh (OBJ) and the hair file if the
// scene names them, builds or selects the guides. Errors name the file and the scene field.
sim::SimSetup load_sim_setup(const Scene& scene);

}  // namespace wisp::io
