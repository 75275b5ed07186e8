// Blur values on wisp outlines (see hair_blur.hpp).
#include "vector/hair_blur.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "vector/wisp_chart.hpp"

namespace wisp::vector {
namespace {

using Eigen::Vector2d;

// Pixels moved per frame by the samples of one strand (empty: unknown).
std::vector<double> sample_speeds(const sim::ProjectedStrand& s,
                                  const sim::ProjectedStrand* other) {
  std::vector<double> v;
  if (!other || other->pixel.size() != s.pixel.size()) return v;
  for (size_t i = 0; i < s.pixel.size(); ++i) v.push_back((s.pixel[i] - other->pixel[i]).norm());
  return v;
}

double speed_at(const std::vector<double>& speeds, double strand_u) {
  if (speeds.empty()) return 0;
  if (speeds.size() == 1) return speeds[0];
  const double x = std::clamp(strand_u, 0.0, 1.0) * double(speeds.size() - 1);
  const size_t i = std::min(size_t(x), speeds.size() - 2);
  return speeds[i] + (x - double(i)) * (speeds[i + 1] - speeds[i]);
}

}  // namespace

double circle_of_confusion_px(const Lens& lens, double focal_px, double z) {
  return focal_px * lens.aperture * std::abs(1 / lens.focus_distance - 1 / z);
}

bool blurs(const BlurStyle& style, const Lens& lens) {
  return style.tip > 0 || style.shutter > 0 || lens.aperture > 0;
}

std::vector<diffusion::DiffusionCurve> blur_curves(const sim::ProjectedFrame& frame,
                                                   const std::vector<Wisp>& wisps,
                                                   const WispArrangement& arrangement,
                                                   const BlurStyle& style,
                                                   const BlurSources& sources) {
  const auto& visible = arrangement.visible;
  std::vector<diffusion::DiffusionCurve> out;
  if (!blurs(style, sources.lens)) return out;
  std::unordered_map<int, const sim::ProjectedStrand*> strand_of, neighbour_of;
  for (const sim::ProjectedStrand& s : frame.strands) strand_of[s.id] = &s;
  if (sources.neighbour && style.shutter > 0)
    for (const sim::ProjectedStrand& s : sources.neighbour->strands) neighbour_of[s.id] = &s;
  const double scale = std::min(frame.width, frame.height) / style.reference_size;
  const double cap = style.max * scale;
  const Vector2d centre(0.5 * frame.width, 0.5 * frame.height);
  bool any = false;
  for (size_t w = 0; w < wisps.size() && w < visible.size(); ++w) {
    if (visible[w].empty()) continue;
    const Wisp& wisp = wisps[w];
    const auto it = strand_of.find(wisp.strand);
    if (it == strand_of.end()) continue;
    const auto nb = neighbour_of.find(wisp.strand);
    const std::vector<double> speeds =
        sample_speeds(*it->second, nb == neighbour_of.end() ? nullptr : nb->second);
    const WispChart chart(wisp, *it->second, frame.eye);
    diffusion::DiffusionCurve c;
    c.points = wisp.outline.points;
    c.active = visible[w];
    const int k = wisp.outline.piece_count();
    for (int i = 0; i <= k; ++i) {
      const double t = wisp.outline.t[3 * i];
      const double u = chart.strand_u(t);
      double variance = 0;
      if (style.tip > 0) {
        const double r = std::clamp((u - (1 - style.tip_fade)) / style.tip_fade, 0.0, 1.0);
        variance += std::pow(style.tip * scale * r * r * (3 - 2 * r), 2);
      }
      if (sources.lens.aperture > 0) {
        // The planar depth of a pinhole camera's ray through pixel p at distance d.
        const double off = (wisp.outline.points[3 * i] - centre).norm();
        const double z =
            wisp.outline.depth[3 * i] * frame.focal_px / std::hypot(frame.focal_px, off);
        variance += std::pow(circle_of_confusion_px(sources.lens, frame.focal_px, z) / 4, 2);
      }
      if (style.shutter > 0) variance += std::pow(style.shutter * speed_at(speeds, u), 2) / 12;
      const float sigma = float(std::min(cap, std::sqrt(variance)));
      any = any || sigma > 0;
      c.blur.push_back({double(i) / k, sigma});
    }
    out.push_back(std::move(c));
  }
  if (!any) return {};
  for (const InkLine& cut : arrangement.occluder_cuts) {
    const size_t n = cut.points.size() + (cut.closed ? 1 : 0);
    if (n < 2) continue;
    diffusion::DiffusionCurve c;
    c.points = {cut.points[0]};
    for (size_t i = 1; i < n; ++i) {
      const diffusion::Cubic q =
          diffusion::line_cubic(cut.points[i - 1], cut.points[i % cut.points.size()]);
      c.points.insert(c.points.end(), q.begin() + 1, q.end());
    }
    c.blur = {{0.0, 0.0f}};
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace wisp::vector
