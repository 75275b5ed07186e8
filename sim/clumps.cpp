// Clustering a dense groom into clumps and measuring their widths: see clumps.hpp.
#include "sim/clumps.hpp"

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

// The strands as points of R^(3F): F points at equal arc-length fractions, the root scaled by
// sqrt(root_weight) so that plain squared distances are the clustering's distance.
struct Features {
  int dim = 0;
  std::vector<double> x;  // strand i at [i * dim, (i + 1) * dim)
  std::vector<Vector3d> root;

  Features(const std::vector<Polyline>& strands, const ClumpOptions& o) : dim(3 * o.shape_points) {
    x.resize(strands.size() * dim);
    root.reserve(strands.size());
    const double w = std::sqrt(o.root_weight);
    for (std::size_t i = 0; i < strands.size(); ++i) {
      const Polyline p = resample(strands[i], o.shape_points - 1);
      for (int k = 0; k < o.shape_points; ++k)
        for (int a = 0; a < 3; ++a) x[i * dim + 3 * k + a] = (k == 0 ? w : 1.0) * p[k][a];
      root.push_back(p[0]);
    }
  }
  const double* operator[](int i) const { return &x[std::size_t(i) * dim]; }
  double distance(const double* a, const double* b) const {
    double d = 0;
    for (int k = 0; k < dim; ++k) d += (a[k] - b[k]) * (a[k] - b[k]);
    return d;
  }
};

// Cells about the spacing of `count` points spread over the roots' box (roots lie on a surface,
// so its largest side over sqrt(count)).
PointGrid root_grid(const Eigen::AlignedBox3d& box, int count) {
  return PointGrid(box, box.sizes().maxCoeff() / std::sqrt(double(count)));
}

// k-means++ seeding: each new seed is drawn with probability proportional to its squared
// distance from the nearest seed so far. A new seed lowers the distance only of strands whose
// roots lie within reach (the largest distance so far, over the root weight), found on the grid.
std::vector<int> seed_medoids(const Features& f, const PointGrid& strands, int count,
                              const ClumpOptions& o) {
  const int n = int(f.root.size());
  Rng rng(o.seed);
  std::vector<double> nearest(n, std::numeric_limits<double>::infinity());
  std::vector<int> seeds;
  int next = std::min(n - 1, int(rng.uniform() * n));
  double largest = std::numeric_limits<double>::infinity();
  while (true) {
    seeds.push_back(next);
    const double* s = f[next];
    strands.search(
        f.root[next],
        [&](int i, const Vector3d&) { nearest[i] = std::min(nearest[i], f.distance(f[i], s)); },
        [&] { return largest / o.root_weight; });
    if (int(seeds.size()) == count) break;
    double total = 0;
    largest = 0;
    for (double d : nearest) {
      total += d;
      largest = std::max(largest, d);
    }
    if (!(total > 0)) break;  // every strand duplicates a seed: fewer clumps
    const double u = rng.uniform() * total;
    double sum = 0;
    next = -1;
    for (int i = 0; i < n; ++i) {
      if (nearest[i] <= 0) continue;
      next = i;
      sum += nearest[i];
      if (sum > u) break;
    }
  }
  return seeds;
}

}  // namespace

Clumps cluster_strands(const std::vector<Polyline>& strands, const ClumpOptions& o) {
  if (strands.empty()) throw std::invalid_argument("cluster_strands: no strands");
  for (std::size_t i = 0; i < strands.size(); ++i)
    if (strands[i].size() < 2)
      throw std::invalid_argument("cluster_strands: strand " + std::to_string(i) +
                                  " has fewer than 2 points");
  if (o.count < 1 || o.shape_points < 2 || !(o.root_weight > 0) || o.rounds < 0)
    throw std::invalid_argument(
        "cluster_strands: count, shape_points, root_weight or rounds out of range");
  const int n = int(strands.size());
  Clumps out;
  if (o.count >= n) {
    for (int i = 0; i < n; ++i) {
      out.guide.push_back(i);
      out.clump_of.push_back(i);
    }
    return out;
  }

  const Features f(strands, o);
  Eigen::AlignedBox3d box;
  for (const Vector3d& r : f.root) box.extend(r);
  PointGrid strand_grid = root_grid(box, o.count);
  for (int i = 0; i < n; ++i) strand_grid.insert(f.root[i], i);
  std::vector<int>& medoid = out.guide;
  medoid = seed_medoids(f, strand_grid, o.count, o);
  const int k = int(medoid.size());
  std::vector<int>& clump = out.clump_of;
  clump.assign(n, 0);

  const auto assign = [&] {
    PointGrid grid = root_grid(box, k);
    for (int c = 0; c < k; ++c) grid.insert(f.root[medoid[c]], c);
    for (int i = 0; i < n; ++i) {
      double best = std::numeric_limits<double>::infinity();
      int best_c = 0;
      grid.search(
          f.root[i],
          [&](int c, const Vector3d&) {
            const double d = f.distance(f[i], f[medoid[c]]);
            if (d < best || (d == best && c < best_c)) {
              best = d;
              best_c = c;
            }
          },
          [&] { return best / o.root_weight; });
      clump[i] = best_c;
    }
    for (int c = 0; c < k; ++c) clump[medoid[c]] = c;  // duplicates of a medoid stay apart
  };
  // Each medoid moves to the member nearest the mean of its clump; true if one moved.
  const auto update = [&] {
    std::vector<double> mean(std::size_t(k) * f.dim, 0.0);
    std::vector<int> size(k, 0);
    for (int i = 0; i < n; ++i) {
      ++size[clump[i]];
      for (int a = 0; a < f.dim; ++a) mean[std::size_t(clump[i]) * f.dim + a] += f[i][a];
    }
    for (int c = 0; c < k; ++c)
      for (int a = 0; a < f.dim; ++a) mean[std::size_t(c) * f.dim + a] /= size[c];
    std::vector<double> best(k, std::numeric_limits<double>::infinity());
    std::vector<int> next(k, -1);
    for (int i = 0; i < n; ++i) {
      const int c = clump[i];
      const double d = f.distance(f[i], &mean[std::size_t(c) * f.dim]);
      if (d < best[c]) {
        best[c] = d;
        next[c] = i;
      }
    }
    const bool moved = next != medoid;
    medoid = next;
    return moved;
  };
  for (int round = 0;; ++round) {
    assign();
    if (round == o.rounds || !update()) break;
  }
  return out;
}

std::vector<double> clump_width(const Polyline& guide, const std::vector<Polyline>& strands,
                                const std::vector<int>& members, double coverage,
                                double min_width) {
  if (guide.size() < 2)
    throw std::invalid_argument("clump_width: the guide has fewer than 2 points");
  if (!(coverage > 0 && coverage <= 1))
    throw std::invalid_argument("clump_width: coverage must be in (0, 1]");
  const int segments = int(guide.size()) - 1;
  std::vector<std::vector<double>> gathered(guide.size());
  for (int m : members)
    for (const Vector3d& p : strands.at(m)) {
      double best = std::numeric_limits<double>::infinity();
      int best_k = 0;
      for (int k = 0; k < segments; ++k) {
        const Vector3d e = guide[k + 1] - guide[k];
        const double len2 = e.squaredNorm();
        const double t = len2 > 0 ? std::clamp((p - guide[k]).dot(e) / len2, 0.0, 1.0) : 0.0;
        const double d = (p - (guide[k] + t * e)).squaredNorm();
        if (d < best) {
          best = d;
          best_k = k;
        }
      }
      gathered[best_k].push_back(std::sqrt(best));
      gathered[best_k + 1].push_back(std::sqrt(best));
    }
  std::vector<double> width(guide.size(), min_width);
  for (std::size_t j = 0; j < guide.size(); ++j) {
    std::vector<double>& d = gathered[j];
    if (d.empty()) continue;
    const std::size_t q = std::size_t(std::ceil(coverage * double(d.size()))) - 1;
    std::nth_element(d.begin(), d.begin() + std::min(q, d.size() - 1), d.end());
    width[j] = std::max(min_width, 2 * d[std::min(q, d.size() - 1)]);
  }
  return width;
}

}  // namespace wisp::sim
