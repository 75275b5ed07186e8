// Measures that several end-to-end tests take of frames: how two masks overlap, and how far a
// point lies from the edges of polygon rings (a mask's outline, a region's boundary).
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

namespace wisp::test {

// Intersection over union of two 8-bit masks (nonzero: set); 1 when both are empty.
double mask_iou(const cv::Mat& a, const cv::Mat& b);

// The distance from p to the nearest edge of the closed rings.
double distance_to_rings(const std::vector<std::vector<Eigen::Vector2d>>& rings,
                         const Eigen::Vector2d& p);

}  // namespace wisp::test
