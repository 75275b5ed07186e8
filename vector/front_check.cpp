// Fronts against the depths at random points (see front_check.hpp).
#include "vector/front_check.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include "vector/band_depth.hpp"
#include "vector/polygon.hpp"

namespace wisp::vector {

using Eigen::Vector2d;

namespace {

// Whether p is inside the rings (even-odd over all of them), and its distance to their nearest
// edge.
std::pair<bool, double> locate(const std::vector<const std::vector<Vector2d>*>& rings,
                               const Vector2d& p) {
  bool in = false;
  double margin = INFINITY;
  for (const auto* ring : rings) {
    in ^= inside_polygon(*ring, p);
    for (size_t i = 0, j = ring->size() - 1; i < ring->size(); j = i++) {
      const Vector2d &a = (*ring)[j], ab = (*ring)[i] - a;
      const double l = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
      margin = std::min(margin, (a + l * ab - p).norm());
    }
  }
  return {in, margin};
}

}  // namespace

FrontCheck check_fronts(const std::vector<Wisp>& wisps, const ArrangementView& view,
                        const std::vector<Occluder>& occluders, const FrontCheckOptions& options) {
  FrontCheck c;
  std::mt19937 rng(options.seed);
  std::uniform_real_distribution<double> unit(0, 1);
  for (const ViewFace& f : view.faces) {
    if (f.cover.empty() || f.outer.empty() || !f.in_view) continue;
    std::vector<const std::vector<Vector2d>*> rings = {&f.outer};
    Eigen::AlignedBox2d box;
    for (const Vector2d& p : f.outer) box.extend(p);
    double area = std::abs(signed_area(f.outer));
    for (const auto& h : f.holes) rings.push_back(&h), area -= std::abs(signed_area(h));
    ++c.faces;
    c.covered_area += area;
    int tried = 0, wrong = 0;
    for (int k = 0; k < options.points_per_face; ++k) {
      const Vector2d p = box.min() + Vector2d(unit(rng), unit(rng)).cwiseProduct(box.sizes());
      const auto [in, inside] = locate(rings, p);
      if (!in || inside < 1e-3 || (options.skip && options.skip(p))) continue;
      double best = INFINITY, second = INFINITY;
      int nearest = -1;
      const auto consider = [&](double z, int id) {
        if (z < best)
          second = best, best = z, nearest = id;
        else
          second = std::min(second, z);
      };
      for (const auto& [w, winding] : f.cover) consider(band_depth(wisps[w], p).depth, w);
      for (const Occluder& o : occluders)
        if (o.depth && locate({&o.ring}, p).first) consider(o.depth(p), -1);
      if (second - best < 1e-9 * best) continue;
      ++tried;
      wrong += nearest != f.front;
    }
    c.points += tried, c.wrong_points += wrong, c.wrong_faces += wrong > 0;
    if (tried > 0) c.wrong_area += area * wrong / tried;
  }
  return c;
}

}  // namespace wisp::vector
