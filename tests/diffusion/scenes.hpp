// Test drawings for the diffusion tests: seeded random curve layouts and small named shapes.
#pragma once

#include <cmath>
#include <random>
#include <vector>

#include "diffusion/diffusion_curve.hpp"

namespace wisp::test {

using diffusion::Color;
using diffusion::DiffusionCurve;

// A closed circle of 4 cubic arcs, counter-clockwise on screen... see the left-side rule in
// diffusion_curve.hpp: travelling with increasing angle in y-down pixel coordinates, the left
// side (-d.y, d.x) points to the centre.
inline DiffusionCurve circle(double cx, double cy, double r, Color inside, Color outside) {
  DiffusionCurve c;
  const double k = 0.5522847498 * r;  // cubic approximation of a quarter circle
  const double pts[13][2] = {{r, 0},   {r, k},   {k, r},  {0, r},  {-k, r}, {-r, k}, {-r, 0},
                             {-r, -k}, {-k, -r}, {0, -r}, {k, -r}, {r, -k}, {r, 0}};
  for (const auto& p : pts) c.points.emplace_back(cx + p[0], cy + p[1]);
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
