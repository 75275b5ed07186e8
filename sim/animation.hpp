// The output of the simulation and the content of a saved .wsim file (io/anim_file.hpp): per frame
// the head pose and every guide strand as a world-space polyline, root first. Plain data; the
// camera projection (sim/camera.hpp) turns a StrandFrame into a ProjectedFrame.
#pragma once

#include <string>
#include <vector>

#include "sim/hair_model.hpp"
#include "sim/head.hpp"

namespace wisp::sim {

struct StrandFrame {
  int frame = 0;
  double time = 0;  // seconds
  HeadPose head;
  std::vector<Polyline> strands;  // world metres, root first; same counts in every frame
};

struct Animation {
  double fps = 24;
  HeadGeometry head;  // what the strands collided with; the renderer's occlusion tests use it too
  // Per strand, per sample: the full width (m) of the clump the guide stands for; empty when the
  // wisps take the style's width (sim::SimSetup::widths).
  std::vector<std::vector<double>> widths;
  std::vector<StrandFrame> frames;
};

}  // namespace wisp::sim
