// Simple facial features: brows, upper lids, irises, nose and mouth as ink lines lying on the
// head's surface, so they turn with the head and a turn reads even on a featureless ellipsoid.
// Each line is a few control directions from the head's centre (azimuth towards the head's +x,
// elevation towards +y, from the face direction +z), a centripetal Catmull-Rom curve between
// them sampled finely, each sample placed on the surface (HeadShape::surface_point), with a
// width in metres. Per frame the samples are posed and projected; a sample shows where the
// surface faces the camera (the line thins out towards the outline instead of popping) and no
// drawn solid lies between it and the eye (BodyModel::blocks). The visible runs go to the
// renderer, which draws them in the body layer, under the hair.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <vector>

#include "sim/camera.hpp"
#include "sim/head.hpp"

namespace wisp::sim {

enum class Feature { Brow, Lid, Iris, Nose, Mouth };

// One feature line, head-local: points on the surface and the line's width at each (m).
struct FaceLine {
  Feature feature = Feature::Brow;
  std::vector<Eigen::Vector3d> points, normals;  // normals: unit, outward
  std::vector<double> width;
};

// The features of a head (scaled with it: they are placed by direction).
std::vector<FaceLine> face_lines(const HeadShape& head);

// A visible run of a feature line in the image: pixels (x right, y down) and widths in pixels.
struct FaceStroke {
  Feature feature = Feature::Brow;
  std::vector<Eigen::Vector2d> points;
  std::vector<double> width;
};

// The visible runs of `lines` on a head posed by `pose`. `hidden(x)` says whether world point x
// (on the head) is hidden from the eye by a solid. The width fades with the cosine between the
// surface normal and the direction to the eye, from full at 0.35 to nothing at 0.05.
template <class Hidden>
std::vector<FaceStroke> project_face(const std::vector<FaceLine>& lines, const HeadPose& pose,
                                     const Camera& camera, const Hidden& hidden) {
  std::vector<FaceStroke> out;
  for (const FaceLine& line : lines) {
    FaceStroke run{line.feature, {}, {}};
    const auto flush = [&] {
      if (run.points.size() >= 2) out.push_back(run);
      run = FaceStroke{line.feature, {}, {}};
    };
    for (std::size_t i = 0; i < line.points.size(); ++i) {
      const Eigen::Vector3d x = pose.to_world(line.points[i]);
      const Eigen::Vector3d n = pose.rotation * line.normals[i];
      const Eigen::Vector3d to_eye = camera.eye - x;
      const double facing = n.dot(to_eye) / to_eye.norm();
      if (facing < 0.05 || (x - camera.eye).dot(camera.forward) < 1e-3 || hidden(x)) {
        flush();
        continue;
      }
      double depth = 0;
      run.points.push_back(camera.project(x, &depth));
      const double fade = std::min(1.0, (facing - 0.05) / 0.3);
      run.width.push_back(line.width[i] * camera.focal_px / depth * fade);
    }
    flush();
  }
  return out;
}

}  // namespace wisp::sim
