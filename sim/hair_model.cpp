// The procedural hair generator and guide tools: see hair_model.hpp.
#include "sim/hair_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "sim/point_grid.hpp"
#include "sim/rng.hpp"

namespace wisp::sim {
namespace {

using Eigen::Vector3d;

Vector3d random_direction(Rng& rng) {
  const double z = rng.uniform(-1, 1), phi = rng.uniform(0, 2 * M_PI);
  const double r = std::sqrt(std::max(0.0, 1 - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

bool on_scalp(const Vector3d& d, const HairParams& h) {
  const double from_crown = std::acos(std::clamp(d.y(), -1.0, 1.0)) * 180 / M_PI;
  const double from_face = std::acos(std::clamp(d.z(), -1.0, 1.0)) * 180 / M_PI;
  return from_crown <= h.scalp_angle_deg && from_face >= h.face_angle_deg;
}

// Mitchell's best-candidate sampling: each new root is the candidate farthest from the roots
// already placed, which spreads them like blue noise without a radius to tune. The nearest root
// comes from a grid whose cells shrink as roots are added (rebuilt at each doubling, cells about
// the spacing of the roots so far): the same roots as a scan of all of them, in O(n log n).
std::vector<Vector3d> scalp_roots(const HairParams& h, const HeadShape& head, Rng& rng) {
  constexpr int kCandidates = 24;
  std::vector<Vector3d> roots;
  const Eigen::AlignedBox3d box(head.center() - 1.01 * head.half_extent(),
                                head.center() + 1.01 * head.half_extent());
  const double area = 4 * M_PI * head.half_extent().squaredNorm() / 3;  // the surface, roughly
  PointGrid grid(box, 1.0);
  std::size_t rebuild_at = 1;
  const auto nearest_root = [&](const Vector3d& p) {
    double nearest = std::numeric_limits<double>::max();
    grid.search(
        p, [&](int, const Vector3d& r) { nearest = std::min(nearest, (p - r).squaredNorm()); },
        [&] { return nearest; });
    return nearest;
  };
  const auto draw = [&]() {
    for (int tries = 0; tries < 100000; ++tries) {
      const Vector3d d = random_direction(rng);
      if (on_scalp(d, h)) return head.surface_point(d);
    }
    throw std::invalid_argument(
        "hair.scalp_angle_deg / hair.face_angle_deg: the scalp region is empty");
  };
  for (int i = 0; i < h.count; ++i) {
    Vector3d best = draw();
    double best_d = -1;
    for (int c = 0; c < (i == 0 ? 1 : kCandidates); ++c) {
      const Vector3d p = c == 0 ? best : draw();
      const double nearest = nearest_root(p);
      if (nearest > best_d) {
        best_d = nearest;
        best = p;
      }
    }
    roots.push_back(best);
    if (roots.size() >= rebuild_at) {
      rebuild_at *= 2;
      grid = PointGrid(box, std::sqrt(area / double(rebuild_at)));
      for (std::size_t r = 0; r < roots.size(); ++r) grid.insert(roots[r], int(r));
    } else {
      grid.insert(best, int(roots.size()) - 1);
    }
  }
  return roots;
}

// Any unit vector perpendicular to t.
Vector3d perpendicular(const Vector3d& t) {
  const Vector3d a = std::abs(t.x()) < 0.9 ? Vector3d::UnitX() : Vector3d::UnitY();
  return (a - a.dot(t) * t).normalized();
}

// Rotates u by the smallest rotation taking unit a to unit b (parallel transport).
Vector3d transport(const Vector3d& u, const Vector3d& a, const Vector3d& b) {
  const Eigen::Quaterniond q = Eigen::Quaterniond::FromTwoVectors(a, b);
  return q * u;
}

// One strand: the combed centre line, then the wave or curl offset, then equal-arc resampling.
Polyline grow_strand(const HairParams& h, const HeadShape& head, const Vector3d& root,
                     double length, double clearance) {
  Vector3d n;
  head.distance(root, &n);
  // Parting plane through the head's y axis, turned by parting_deg; strands are combed away
  // from it.
  const double a = h.parting_deg * M_PI / 180;
  const Vector3d parting_normal(std::cos(a), 0, -std::sin(a));
  const double side = parting_normal.dot(root - head.center()) >= 0 ? 1.0 : -1.0;
  Vector3d lateral = side * parting_normal;
  lateral = (lateral - lateral.dot(n) * n);
  if (lateral.norm() > 1e-9) lateral.normalize();
  // Gravity comb: down, away from the parting, and back for roots near the face.
  const Vector3d comb_dir = (Vector3d(0, -1, 0) + 0.45 * side * parting_normal -
                             0.6 * std::max(0.0, n.z()) * Vector3d::UnitZ())
                                .normalized();

  const double step = std::min(0.002, length / (4.0 * h.segments));
  const double comb_length = 0.05;  // metres over which a strand turns towards comb_dir
  Polyline line{root};
  Vector3d d = (n + 0.8 * lateral).normalized();
  Vector3d p = root;
  double s = 0;
  while (s < length) {
    d = (d + h.comb * (step / comb_length) * comb_dir).normalized();
    Vector3d q = p + std::min(step, length - s) * d;
    Vector3d nq;
    const double phi = head.distance(q, &nq);
    if (phi < clearance) q += (clearance - phi) * nq;  // slide over the scalp
    s += (q - p).norm();
    if ((q - p).norm() > 1e-12) d = (q - p).normalized();
    p = q;
    line.push_back(p);
  }

  if (h.style != HairCurl::Straight && h.amplitude > 0 && h.frequency > 0) {
    // Offsets in a parallel-transported frame (u starts sideways, across the lay of the hair),
    // faded in over the first 3 cm so roots sit on the scalp.
    Vector3d t0 = (line[1] - line[0]).normalized();
    Vector3d u = lateral - lateral.dot(t0) * t0;
    u = u.norm() > 1e-9 ? Vector3d(u.normalized()) : perpendicular(t0);
    Polyline out{line[0]};
    double arc = 0;
    Vector3d t_prev = t0;
    for (std::size_t i = 1; i < line.size(); ++i) {
      const Vector3d t = (line[i] - line[i - 1]).normalized();
      u = transport(u, t_prev, t);
      u = (u - u.dot(t) * t).normalized();
      t_prev = t;
      arc += (line[i] - line[i - 1]).norm();
      const Vector3d v = t.cross(u);
      const double x = std::clamp(arc / 0.03, 0.0, 1.0);
      const double fade = x * x * (3 - 2 * x);
      const double phase = 2 * M_PI * h.frequency * arc;
      Vector3d offset = h.style == HairCurl::Wavy
                            ? Vector3d(std::sin(phase) * u)
                            : Vector3d((std::cos(phase) - 1) * u + std::sin(phase) * v);
      out.push_back(line[i] + h.amplitude * fade * offset);
    }
    line = std::move(out);
  }
  Polyline strand = resample(line, h.segments);
  clear_head(strand, head, clearance);
  return strand;
}

}  // namespace

std::vector<Polyline> generate_hair(const HairParams& hair, const HeadShape& head,
                                    double clearance) {
  validate_part(hair, "hair");
  Rng rng(hair.seed);
  const std::vector<Vector3d> roots = scalp_roots(hair, head, rng);
  std::vector<Polyline> strands;
  strands.reserve(roots.size());
  for (const Vector3d& root : roots) {
    const double length =
        hair.length * (1 + rng.uniform(-hair.length_variation, hair.length_variation));
    strands.push_back(grow_strand(hair, head, root, length, clearance));
  }
  return strands;
}

std::vector<int> select_guides(const std::vector<Polyline>& strands, int count) {
  std::vector<int> chosen;
  const int n = static_cast<int>(strands.size());
  if (count <= 0 || count >= n) {
    for (int i = 0; i < n; ++i) chosen.push_back(i);
    return chosen;
  }
  int first = 0;
  for (int i = 1; i < n; ++i)
    if (strands[i][0].y() > strands[first][0].y()) first = i;
  std::vector<double> nearest(n, std::numeric_limits<double>::max());
  int next = first;
  for (int c = 0; c < count; ++c) {
    chosen.push_back(next);
    int far = -1;
    for (int i = 0; i < n; ++i) {
      nearest[i] = std::min(nearest[i], (strands[i][0] - strands[next][0]).squaredNorm());
      if (far < 0 || nearest[i] > nearest[far]) far = i;
    }
    next = far;
  }
  return chosen;
}

Polyline resample(const Polyline& strand, int segments) {
  if (strand.size() < 2 || segments < 1)
    throw std::invalid_argument("resample: a strand needs 2 points and at least 1 segment");
  std::vector<double> arc(strand.size(), 0.0);
  for (std::size_t i = 1; i < strand.size(); ++i)
    arc[i] = arc[i - 1] + (strand[i] - strand[i - 1]).norm();
  Polyline out{strand.front()};
  std::size_t j = 1;
  for (int k = 1; k < segments; ++k) {
    const double target = arc.back() * k / segments;
    while (j + 1 < strand.size() && arc[j] < target) ++j;
    const double span = arc[j] - arc[j - 1];
    const double f = span > 0 ? (target - arc[j - 1]) / span : 0.0;
    out.push_back(strand[j - 1] + f * (strand[j] - strand[j - 1]));
  }
  out.push_back(strand.back());
  return out;
}

void clear_head(Polyline& strand, const HeadShape& head, double clearance) {
  for (std::size_t i = 1; i < strand.size(); ++i)
    for (int it = 0; it < 4; ++it) {
      Vector3d n;
      const double phi = head.distance(strand[i], &n);
      if (phi >= clearance) break;
      strand[i] += (clearance - phi) * n;
    }
}

double curl_amplitude(const Polyline& strand, int half) {
  double sum = 0;
  int n = 0;
  for (int i = half; i + half < static_cast<int>(strand.size()); ++i) {
    sum += (strand[i] - 0.5 * (strand[i - half] + strand[i + half])).norm() / 2;
    ++n;
  }
  return n > 0 ? sum / n : 0.0;
}

}  // namespace wisp::sim
