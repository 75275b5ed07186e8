// Gradient meshes (diffusion_curve.hpp) as the solve sees them, following small-usvg (Tian and
// Guenther, "Unified Smooth Vector Graphics", TVCG 2025).
//
// Each tile is a Ferguson patch: bicubic Hermite interpolation of its four corners' values and
// u, v tangents with zero twist, for the position and for the colour alike. Missing position
// tangents, and every colour tangent, are central differences over the neighbouring vertices in
// index space (one-sided at the border), which is what small-usvg does.
//
// In the solve (rasterize.hpp) a mesh is
//  - its outline: one closed curve round the mesh, in small-usvg's order (the row v = 1 along u,
//    the column u = 1 back down v, the row v = 0 back along u, the column u = 0 up v), whose
//    right side is a Dirichlet boundary holding the mesh's colour along it and whose left side is
//    a Neumann barrier. For a mesh whose u, v axes turn like x, y (all published meshes) the right
//    side is the inside: the mesh is insulated from what surrounds it;
//  - its inside: every pixel whose centre the mesh covers gets as Poisson source the discrete
//    Laplacian of the mesh colour, over the same links and anchors the pixel has. A mesh alone
//    therefore solves to its own colours exactly, and curves drawn over it bend them smoothly,
//    as in the unified Poisson formulation. Where meshes overlap, the last one in drawing order
//    owns the pixel; inside one mesh whose tiles fold over, the first tile does.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "diffusion/diffusion_curve.hpp"

namespace wisp::diffusion {

// A mesh in pixel coordinates with every tangent set; vertex (i, j) is index j * (cols+1) + i,
// i along u, j along v.
struct MeshGeometry {
  int rows = 0;
  int cols = 0;
  std::vector<Eigen::Vector2d> p, pu, pv;
  std::vector<Eigen::Vector3d> c, cu, cv;
};

// Scales a valid mesh into pixels: normalized positions by the drawing's size first, then all by
// `scale` (pixels per drawing unit along x and y).
MeshGeometry resolve_mesh(const GradientMesh& mesh, const Eigen::Vector2d& drawing_size,
                          const Eigen::Vector2d& scale);

// Position, its partial derivatives, and colour of tile (i, j) at (u, v) in [0,1]^2.
Eigen::Vector2d mesh_position(const MeshGeometry& g, int i, int j, double u, double v);
Eigen::Matrix2d mesh_jacobian(const MeshGeometry& g, int i, int j, double u, double v);
Eigen::Vector3d mesh_color(const MeshGeometry& g, int i, int j, double u, double v);

// The outline (see above) as a closed diffusion curve tagged with `index`; its colour along each
// tile edge is sampled `stops_per_edge` times.
DiffusionCurve mesh_outline(const MeshGeometry& g, int index, int stops_per_edge = 16);

// Which mesh covers each pixel centre (-1: none) and its colour there (3 planes of W*H).
struct MeshRaster {
  int width = 0;
  int height = 0;
  std::vector<int> owner;
  std::vector<float> planes;
};
MeshRaster rasterize_meshes(const std::vector<MeshGeometry>& meshes, int width, int height);

}  // namespace wisp::diffusion
