// Test drawings for the diffusion tests: seeded random curve layouts and small named shapes.
#pragma once

#include <cmath>
#include <random>
#include <vector>

#include "diffusion/diffusion_curve.hpp"

namespace wisp::test {

using diffusion::Color;
using diffusion::DiffusionCurve;

// A closed circle of `arcs` cubic arcs (4 stray from the circle by 2.7e-4 r, 8 by 4e-6 r, 16 by
// 7e-8 r), counter-clockwise on screen... see the left-side rule in diffusion_curve.hpp:
// travelling with increasing angle in y-down pixel coordinates, the left side (-d.y, d.x) points
// to the centre.
inline DiffusionCurve circle(double cx, double cy, double r, Color inside, Color outside,
                             int arcs = 4) {
  DiffusionCurve c;
  const double step = 2 * 3.14159265358979323846 / arcs;
  const double k = 4.0 / 3.0 * std::tan(step / 4);  // tangent length of a cubic arc, over r
  const auto at = [&](double a, double along) {
    return Eigen::Vector2d(cx + r * (std::cos(a) - along * std::sin(a)),
                           cy + r * (std::sin(a) + along * std::cos(a)));
  };
  c.points.push_back(at(0, 0));
  for (int s = 0; s < arcs; ++s) {
    const double a0 = s * step, a1 = (s + 1) * step;
    c.points.push_back(at(a0, k));
    c.points.push_back(at(a1, -k));
    c.points.push_back(s + 1 == arcs ? c.points.front() : at(a1, 0));
  }
  c.left = {{0, inside}, {1, inside}};
  c.right = {{0, outside}, {1, outside}};
  return c;
}

// A random open cubic path of `segments` segments inside [0,size]^2 with random colour stops.
inline DiffusionCurve random_curve(std::mt19937& rng, double size, int segments) {
  std::uniform_real_distribution<double> pos(0.05 * size, 0.95 * size), step(-0.25, 0.25),
      unit(0, 1);
  DiffusionCurve c;
  Eigen::Vector2d p(pos(rng), pos(rng));
  c.points.push_back(p);
  for (int s = 0; s < 3 * segments; ++s) {
    p += Eigen::Vector2d(step(rng), step(rng)) * size;
    p = p.cwiseMax(0.02 * size).cwiseMin(0.98 * size);
    c.points.push_back(p);
  }
  const auto colour = [&] { return Color(float(unit(rng)), float(unit(rng)), float(unit(rng))); };
  c.left = {{0, colour()}, {0.5, colour()}, {1, colour()}};
  c.right = {{0, colour()}, {1, colour()}};
  return c;
}

}  // namespace wisp::test
