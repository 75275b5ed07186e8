// From a scene to the simulator's input and the renderer's body and projection settings:
// load_sim_setup reads the files the scene names (head mesh, strand file) and builds or selects
// the guides; body_params and projector_options say what is drawn and what hides the hair.
#pragma once

#include "io/scene.hpp"
#include "sim/body.hpp"
#include "sim/camera.hpp"
#include "sim/simulate.hpp"

namespace wisp::render {

// Everything the simulator needs from a scene: reads the head mesh (OBJ) and the hair file if the
// scene names them, builds or selects the guides. Errors name the file and the scene field.
sim::SimSetup load_sim_setup(const io::Scene& scene);

// The body the scene draws (render.body, render.torso) around its head (sim::body_params): all
// parts off when render.body is false.
sim::BodyParams body_params(const io::Scene& scene);

// Projector options for the scene: its light, and its drawn neck and torso as occluders.
sim::ProjectorOptions projector_options(const io::Scene& scene);

}  // namespace wisp::render
