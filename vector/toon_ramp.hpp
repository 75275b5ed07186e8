// A 2D toon ramp (X-Toon: Barla, Thollot and Markosian, NPAR 2006; used by Costigan 2013): an
// image whose x axis is the light intensity (0 left, 1 right) and whose y axis is a second metric
// (0 top row, 1 bottom row): depth detail, back light or specular. The colour at (x, y) is the
// hair's colour there.
//
// Hard toon bands are the ramp's columns where the colour jumps: between columns c-1 and c when
// some row changes by more than a threshold (largest channel difference). Inside one band the
// ramp is interpolated bilinearly, never across a band edge, so a lookup on either side of an
// edge gives that side's colour exactly and the renderer can put a sharp curve there.
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "sim/choices.hpp"

namespace wisp::vector {

enum class RampMetric { None, Depth, BackLight, Specular };
constexpr std::array<sim::Choice<RampMetric>, 4> choices(RampMetric) {
  return {{{"none", RampMetric::None},
           {"depth", RampMetric::Depth},
           {"back_light", RampMetric::BackLight},
           {"specular", RampMetric::Specular}}};
}

struct ToonRamp {
  int width = 0, height = 0;
  std::vector<Eigen::Vector3f> pixels;  // row-major, row 0 at the top (metric 0)
  std::string source;                   // the file it came from, for messages

  const Eigen::Vector3f& at(int column, int row) const {
    return pixels[size_t(row) * width + column];
  }
};

// A ramp with its band edges found once (see above).
class RampBands {
 public:
  RampBands(const ToonRamp& ramp, double jump_threshold);

  // Band edges as ramp x positions (edge at column c: x = c / width), ascending.
  const std::vector<double>& edges() const { return edge_x_; }
  int band(double x) const;  // number of edges at or left of x
  // Colour at (x, y) interpolated inside band `band` only (x is clamped into it).
  Eigen::Vector3f lookup(double x, double y, int band) const;
  Eigen::Vector3f lookup(double x, double y) const { return lookup(x, y, band(x)); }

 private:
  const ToonRamp& ramp_;
  std::vector<int> edge_col_;  // first column of each band after the first
  std::vector<double> edge_x_;
};

}  // namespace wisp::vector
