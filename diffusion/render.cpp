// render_drawing: rasterize, solve, reblur (see render.hpp). Gradient meshes enter as their
// outlines and their coverage (gradient_mesh.hpp), Poisson curves as gradient curves whose jump
// is their weight (diffusion_curve.hpp).
#include "diffusion/render.hpp"

#include <stdexcept>
#include <string>

#include "diffusion/blur.hpp"
#include "diffusion/gradient_mesh.hpp"
#include "diffusion/timer.hpp"

namespace wisp::diffusion {
namespace {

// small-usvg's weights are for a 1024 x 1024 drawing: the step across a Poisson curve is the
// weight times the drawing's area over this.
constexpr double kPoissonReferenceArea = 1024.0 * 1024.0;

DiffusionCurve gradient_curve(const PoissonCurve& p, const Eigen::Vector2d& scale, double jump) {
  DiffusionCurve c;
  c.gradient_only = true;
  c.points = p.points;
  for (Eigen::Vector2d& q : c.points) q = q.cwiseProduct(scale);
  c.right = p.weights;  // the jump is right - left, with left black
  for (ColorStop& s : c.right) s.color *= float(jump);
  return c;
}

}  // namespace

Image render_drawing(const Drawing& drawing, int width, int height, const SolverOptions& solver,
                     RenderStats* stats, bool antialias) {
  if (drawing.width <= 0 || drawing.height <= 0)
    throw std::invalid_argument("drawing size must be positive");
  RenderStats local;
  RenderStats& st = stats ? *stats : local;

  auto t0 = Clock::now();
  const Eigen::Vector2d scale(double(width) / drawing.width, double(height) / drawing.height);
  // Mesh outlines first (small-usvg's order), then the curves, then the Poisson curves.
  std::vector<DiffusionCurve> curves;
  std::vector<MeshGeometry> meshes;
  const Eigen::Vector2d drawing_size(drawing.width, drawing.height);
  for (size_t i = 0; i < drawing.meshes.size(); ++i) {
    validate(drawing.meshes[i], "gradient mesh " + std::to_string(i + 1));
    meshes.push_back(resolve_mesh(drawing.meshes[i], drawing_size, scale));
    curves.push_back(mesh_outline(meshes.back(), int(i)));
  }
  bool any_blur = false;
  for (size_t i = 0; i < drawing.curves.size(); ++i) {
    validate(drawing.curves[i], "curve " + std::to_string(i + 1));
    curves.push_back(drawing.curves[i]);
    DiffusionCurve& c = curves.back();
    c.mesh_outline = -1;
    for (Eigen::Vector2d& p : c.points) p = p.cwiseProduct(scale);
    for (BlurStop& b : c.blur) {
      b.sigma *= float(scale.mean());
      any_blur = any_blur || b.sigma > 0;
    }
  }
  const double jump = double(drawing.width) * drawing.height / kPoissonReferenceArea;
  for (size_t i = 0; i < drawing.poisson_curves.size(); ++i) {
    validate(drawing.poisson_curves[i], "Poisson curve " + std::to_string(i + 1));
    curves.push_back(gradient_curve(drawing.poisson_curves[i], scale, jump));
  }
  RasterizeOptions raster;
  raster.blur_channel = any_blur;
  // Only with meshes: their coverage is three full-size planes.
  const MeshRaster coverage =
      meshes.empty() ? MeshRaster{} : rasterize_meshes(meshes, width, height);
  const Problem problem =
      rasterize(curves, width, height, raster, meshes.empty() ? nullptr : &coverage);
  st.rasterize_ms = ms_since(t0);

  t0 = Clock::now();
  Solution solution = solve_multigrid(problem, solver);
  st.solver = solution.stats;
  st.solve_ms = ms_since(t0);

  if (antialias) {
    t0 = Clock::now();
    st.antialiased_pixels = diffusion::antialias(curves, width, height, solution.planes).pixels;
    st.antialias_ms = ms_since(t0);
  }

  Image image{width, height, {}};
  const size_t n = size_t(width) * size_t(height);
  if (any_blur) {
    t0 = Clock::now();
    const std::vector<float> sigma(solution.planes.begin() + 3 * n, solution.planes.end());
    solution.planes.resize(3 * n);
    image.planes = spatially_varying_blur(solution.planes, 3, width, height, sigma);
    st.blur_ms = ms_since(t0);
    st.blurred = true;
  } else {
    image.planes = std::move(solution.planes);
  }
  return image;
}

}  // namespace wisp::diffusion
