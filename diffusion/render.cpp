// render_drawing: rasterize, solve, reblur (see render.hpp).
#include "diffusion/render.hpp"

#include <stdexcept>
#include <string>

#include "diffusion/blur.hpp"
#include "diffusion/timer.hpp"

namespace wisp::diffusion {

Image render_drawing(const Drawing& drawing, int width, int height, const SolverOptions& solver,
                     RenderStats* stats, bool antialias) {
  if (drawing.width <= 0 || drawing.height <= 0)
    throw std::invalid_argument("drawing size must be positive");
  RenderStats local;
  RenderStats& st = stats ? *stats : local;

  auto t0 = Clock::now();
  const Eigen::Vector2d scale(double(width) / drawing.width, double(height) / drawing.height);
  std::vector<DiffusionCurve> curves = drawing.curves;
  bool any_blur = false;
  for (size_t i = 0; i < curves.size(); ++i) {
    validate(curves[i], "curve " + std::to_string(i + 1));
    for (Eigen::Vector2d& p : curves[i].points) p = p.cwiseProduct(scale);
    for (BlurStop& b : curves[i].blur) {
      b.sigma *= float(scale.mean());
      any_blur = any_blur || b.sigma > 0;
    }
  }
  RasterizeOptions raster;
  raster.blur_channel = any_blur;
  const Problem problem = rasterize(curves, width, height, raster);
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
