// Runs a strand simulation from a prepared setup to an Animation. The physics advances in fixed
// steps of 1/sim.step_rate seconds (each split into sim.substeps), whatever the frame rate; a frame
// is the state at the step nearest its time. With sim.preroll > 0 the run starts that many seconds
// before frame 0 with the head still at its first pose, so frame 0 shows settled hair. Every step
// is checked: a non-finite position or a sample faster than sim.max_speed stops the run with an
// error naming the frame, so a blown-up integrator never writes NaNs into an animation.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "sim/animation.hpp"
#include "sim/body.hpp"
#include "sim/params.hpp"

namespace wisp::sim {

struct SimSetup {
  HeadGeometry head;
  std::optional<BodyParams> body;  // neck, torso and arm colliders (sim/body.hpp BodyShape)
  std::vector<Keyframe> motion;    // expanded keyframes (sim/motion.hpp)
  double duration = 4.0;           // seconds
  std::vector<Polyline> rest;      // guides at rest, head-local metres, root first
  // Per guide, per rest sample: the full width (m) of the clump it stands for (hair.guides);
  // empty: wisps take the style's width.
  std::vector<std::vector<double>> widths;
  SimParams sim;
};

// Everything but the guides: head (with `mesh` for shape Mesh), body, motion, parameters.
// Throws std::invalid_argument naming the part and field ("sim.fps: ...") for bad parameters.
SimSetup make_base_setup(const HeadParams& head, const MotionParams& motion, const SimParams& sim,
                         const TriangleMesh& mesh = {});

// The setup of a procedural hair model: make_base_setup plus generate_hair's guides, kept
// sim.collision_margin + 2 mm off the head. (Scenes with strand files are prepared by
// render::load_sim_setup, which reads the file first.)
SimSetup make_setup(const HeadParams& head, const HairParams& hair, const MotionParams& motion,
                    const SimParams& sim, const TriangleMesh& mesh = {});

// Called after each frame with (frames done, total frames).
using SimProgress = std::function<void(int done, int total)>;

// Called with each frame as soon as it is simulated, in order (a renderer that starts on the
// first frames while the rest are simulated); an exception it throws stops the simulation.
using SimFrameSink = std::function<void(const StrandFrame& frame)>;

// Throws std::invalid_argument for bad parameters (validate(SimParams), as "sim.step_rate: ...")
// and std::runtime_error when the integrator blows up ("simulation blew up at frame F ...").
Animation simulate(const SimSetup& setup, const SimProgress& progress = {},
                   const SimFrameSink& on_frame = {});

// The number of frames simulate() writes: frame 0 at time 0, then one per 1/fps up to duration.
int animation_frame_count(const SimSetup& setup);

// Largest |segment length / rest length - 1| of any strand in `frame`, against `rest`.
double max_stretch(const StrandFrame& frame, const std::vector<Polyline>& rest);

}  // namespace wisp::sim
