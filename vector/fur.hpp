// Fur tufts as vector shapes: Sheppard's fins in 2D (sim/fur.hpp). Each projected tuft becomes
// one filled path, its strands as tapered closed loops (a quadratic Bezier per strand, raised to
// a cubic and offset to both sides by a half-width falling from the root to a point at the tip),
// with one colour and an opacity. The opacity is the fin's alpha: 1 where the surface is seen
// edge-on (N.V = 0), falling linearly to 0 at |N.V| = `fin_band` (Sheppard's alpha = 1 - 3 |N.V|
// is fin_band 1/3), so a tuft fades in as its root nears the silhouette instead of popping; on
// the front of the head it does not fall below `interior_opacity`, which lays a sparse texture of
// strands over the base coat. The colour is Sheppard's lighting of the tuft as a hair of tangent
// T (root to tip): ambient + shadow (Kajiya-Kay diffuse + Lambert fill of the head's normal)
// taking the style's shadow colour to its hair colour, times the tuft's variance, plus the
// Kajiya-Kay specular in the highlight colour. Tufts come back to front (far roots first, as
// Sheppard sorted his fins), so nearer fur covers farther.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "sim/fur.hpp"

namespace wisp::vector {

struct HairStyle;

// The look of fur tufts (the style's `fur` part).
struct FurStyle {
  double strand_width = 0.0008;  // strand width at the root (m); tips come to a point
  double fin_band = 0.35;        // |N.V| where a tuft's opacity reaches 0
  double interior_opacity = 0;   // the least opacity of a tuft on the front of the head
  double max_opacity = 1;        // opacity of a tuft seen edge-on
  double min_width_px = 0.6;     // strands never narrower at the root than this (px)
};

// Throws std::invalid_argument("fur.field: what").
void validate(const FurStyle& fur);

// One tuft: closed cubic loops (3k+1 control points, last equal to the first), filled together
// with the nonzero rule, in one colour at one opacity.
struct FurTuft {
  int id = 0;  // the tuft's index in its model: stable over the animation
  std::vector<std::vector<Eigen::Vector2d>> loops;
  Eigen::Vector3f color = Eigen::Vector3f::Zero();
  float opacity = 0;
  Eigen::Vector2d root = Eigen::Vector2d::Zero();  // the tuft's root, pixels
};

// The fin opacity at N.V = `facing` (see above).
double fin_opacity(double facing, const FurStyle& fur);

// Sheppard's lighting of fur of unit direction T on skin of unit normal N (world), without the
// specular, as a fraction in [0, 1] of its maximum (see above).
double fur_intensity(const Eigen::Vector3d& T, const Eigen::Vector3d& N, const Eigen::Vector3d& L,
                     const HairStyle& style);

// The coat under the fur (the hair base, lit): at intensity I the colour 2 tone I of the way
// from the shadow to the hair colour (clamped), so half-lit fur has the base's flat tone.
Eigen::Vector3f coat_color(const Eigen::Vector3d& T, const Eigen::Vector3d& N,
                           const Eigen::Vector3d& L, const HairStyle& style);

// Far to near; tufts whose opacity rounds to nothing (< 1/255) are left out.
std::vector<FurTuft> fur_tufts(const sim::ProjectedFur& fur, const HairStyle& style);

}  // namespace wisp::vector
