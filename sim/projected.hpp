// The contract between sim/ and vector/: one frame of guide strands as the camera sees them.
// Plain data (Eigen only, no Bullet), produced by the camera projection in sim/ and consumed by
// the wisp builder in vector/.
//
// Image coordinates are pixels: x to the right, y down, the image covers [0,width]x[0,height].
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace wisp::sim {

// One guide strand, root first. All arrays have one entry per sample.
struct ProjectedStrand {
  int id = 0;                            // guide index, stable over the whole animation
  std::vector<Eigen::Vector2d> pixel;    // projected position (pixels)
  std::vector<double> depth;             // distance from the eye (scene units, > 0)
  std::vector<Eigen::Vector3d> world;    // 3D position (scene units)
  std::vector<Eigen::Vector3d> tangent;  // unit 3D tangent in world space, towards the tip
  std::vector<std::uint8_t> visible;     // 1 where the sample is not hidden by the head
  // Full width (scene units) of the clump this guide stands for, per sample; empty: the wisp
  // takes the style's width and profile.
  std::vector<double> width;
};

struct ProjectedFrame {
  int frame = 0;
  double time = 0;  // seconds
  int width = 0;    // image size in pixels
  int height = 0;
  double focal_px = 0;  // focal length in pixels: a length L at depth z spans L*focal_px/z px
  Eigen::Vector3d eye = Eigen::Vector3d::Zero();         // camera position (world)
  Eigen::Vector3d light_dir = Eigen::Vector3d::UnitZ();  // unit direction towards the light
  Eigen::Vector3d head_up = Eigen::Vector3d::UnitY();    // the head's crown axis (unit, world)
  std::vector<ProjectedStrand> strands;
};

}  // namespace wisp::sim
