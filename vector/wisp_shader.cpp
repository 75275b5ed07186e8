// The colour field of a lit wisp (see wisp_shader.hpp).
#include "vector/wisp_shader.hpp"

#include <Eigen/Dense>
#include <algorithm>

namespace wisp::vector {

WispShader::WispShader(const WispChart& chart, const HairStyle& style, const FrameLight& light,
                       const RampBands* bands)
    : chart_(chart), style_(style), light_(light), bands_(bands) {}

Eigen::Vector3d head_centre_from_roots(const std::vector<Eigen::Vector3d>& roots) {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& r : roots) centroid += r;
  if (roots.empty()) return centroid;
  centroid /= double(roots.size());
  if (roots.size() < 8) return centroid;
  // |p|^2 = 2 c.p + d, linear in (c, d); centred on the centroid for conditioning.
  Eigen::MatrixXd A(roots.size(), 4);
  Eigen::VectorXd b(roots.size());
  double spread = 0;
  for (size_t i = 0; i < roots.size(); ++i) {
    const Eigen::Vector3d p = roots[i] - centroid;
    A.row(i) << 2 * p.x(), 2 * p.y(), 2 * p.z(), 1.0;
    b[i] = p.squaredNorm();
    spread = std::max(spread, p.norm());
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
  if (qr.rank() < 4) return centroid;
  const Eigen::Vector4d x = qr.solve(b);
  const Eigen::Vector3d c = x.head<3>();
  // A nearly flat cap of roots gives a huge sphere: then the centroid is the better guess.
  if (!c.allFinite() || c.norm() > 3 * spread) return centroid;
  return centroid + c;
}

FrameLight frame_light(const sim::ProjectedFrame& frame, const std::vector<Wisp>& wisps,
                       const HairStyle& style) {
  std::vector<Eigen::Vector3d> roots;
  for (const sim::ProjectedStrand& s : frame.strands)
    if (!s.world.empty()) roots.push_back(s.world.front());
  FrameLight light;
  light.head_centre = head_centre_from_roots(roots);
  for (const Eigen::Vector3d& r : roots)
    light.head_radius += (r - light.head_centre).norm() / double(roots.size());
  light.light = frame.light_dir.norm() > 0 ? Eigen::Vector3d(frame.light_dir.normalized())
                                           : Eigen::Vector3d::UnitZ();
  double zmin = 1e300, zmax = 0;
  for (const Wisp& w : wisps)
    for (double z : w.centre.depth) zmin = std::min(zmin, z), zmax = std::max(zmax, z);
  light.z_near = style.shading.depth_near > 0 ? style.shading.depth_near : zmin;
  light.z_far = style.shading.depth_far > 0 ? style.shading.depth_far : zmax;
  return light;
}

double WispShader::x(double t, double u) const {
  const Lighting& m = style_.shading.lighting;
  const double top = max_intensity(m);
  if (top <= 0) return 0;
  double shadow = 1;
  if (m.head_shadow > 0) {
    const Eigen::Vector3d out = chart_.world(t) - light_.head_centre;
    if (out.norm() > 1e-12) shadow = head_shadow(out.normalized(), light_.light, m);
  }
  return std::clamp(intensity(chart_.frame(t), u, light_.light, m, shadow) / top, 0.0, 1.0);
}

double WispShader::y(double t, double u) const {
  const ShadingStyle& s = style_.shading;
  switch (s.metric) {
    case RampMetric::Depth:
      return depth_detail(chart_.depth(t), light_.z_near, light_.z_far);
    case RampMetric::BackLight: {
      const TubeFrame f = chart_.frame(t);
      return back_light(tube_normal(f, u), f.V, s.lighting.back_exponent);
    }
    case RampMetric::Specular: {
      const TubeFrame f = chart_.frame(t);
      return blinn(tube_normal(f, u), light_.light, f.V, s.metric_shininess);
    }
    case RampMetric::None:
      break;
  }
  return 0.5;
}

int WispShader::band(double t, double u) const {
  return bands_ ? bands_->band(x(t, u)) : 0;
}

Eigen::Vector3f WispShader::color_in_band(double t, double u, int band) const {
  const ShadingStyle& s = style_.shading;
  const double xv = x(t, u);
  Eigen::Vector3f c;
  if (bands_ && s.ramp) {
    c = bands_->lookup(xv, y(t, u), band).cwiseProduct(s.ramp_tint);
  } else {
    c = style_.shadow + (style_.hair - style_.shadow) * float(xv);
  }
  if (s.lighting.specular > 0) {
    const TubeFrame f = chart_.frame(t);
    c += style_.specular.color *
         float(s.lighting.specular *
               kajiya_kay_specular(f.T, light_.light, f.V, s.lighting.shininess));
  }
  return c.cwiseMax(0.0f).cwiseMin(1.0f);
}

Eigen::Vector3f WispShader::color(double t, double u) const {
  return color_in_band(t, u, band(t, u));
}

std::vector<diffusion::ColorStop> stops_along(const WispShader& sh,
                                              const std::vector<Eigen::Vector2d>& tu,
                                              const std::vector<double>& s) {
  std::vector<diffusion::ColorStop> out;
  const RampBands* bands = sh.bands();
  int prev_band = 0;
  for (size_t i = 0; i < tu.size(); ++i) {
    const int b = sh.band(tu[i].x(), tu[i].y());
    if (i > 0 && bands && b != prev_band) {
      // Each edge between the two bands, in the order the segment crosses them.
      const int step = b > prev_band ? 1 : -1;
      double lo_f = 0;
      for (int from = prev_band; from != b; from += step) {
        const double edge = bands->edges()[step > 0 ? from : from - 1];
        double lo = lo_f, hi = 1;
        const auto x_at = [&](double f) {
          const Eigen::Vector2d p = tu[i - 1] + f * (tu[i] - tu[i - 1]);
          return sh.x(p.x(), p.y());
        };
        const bool rising = step > 0;
        for (int k = 0; k < 16; ++k) {
          const double m = 0.5 * (lo + hi);
          ((x_at(m) < edge) == rising ? lo : hi) = m;
        }
        const double f = 0.5 * (lo + hi);
        lo_f = f;
        const Eigen::Vector2d p = tu[i - 1] + f * (tu[i] - tu[i - 1]);
        const double sc = s[i - 1] + f * (s[i] - s[i - 1]);
        out.push_back({sc, sh.color_in_band(p.x(), p.y(), from)});
        out.push_back({sc, sh.color_in_band(p.x(), p.y(), from + step)});
      }
    }
    out.push_back({s[i], sh.color_in_band(tu[i].x(), tu[i].y(), b)});
    prev_band = b;
  }
  for (size_t i = 1; i < out.size(); ++i) out[i].t = std::max(out[i].t, out[i - 1].t);
  return out;
}

}  // namespace wisp::vector
