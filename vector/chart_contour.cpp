// Marching squares on a wisp's chart (see chart_contour.hpp).
#include "vector/chart_contour.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace wisp::vector {

using Eigen::Vector2d;

namespace {

// Grid edges: horizontal (t direction) edge (i, j) joins (i, j) - (i+1, j); vertical edge (i, j)
// joins (i, j) - (i, j+1).
struct Crossing {
  long id = -1;
  Vector2d tu;
};

}  // namespace

std::vector<ChartContour> chart_contours(const ChartGrid& g, double level,
                                         const std::function<double(double, double)>& exact) {
  const long nt = long(g.t.size()), nu = long(g.u.size());
  std::vector<ChartContour> out;
  if (nt < 2 || nu < 2) return out;
  const auto high = [&](long i, long j) { return g.at(i, j) >= level; };
  const auto h_id = [&](long i, long j) { return 2 * (i * nu + j); };
  const auto v_id = [&](long i, long j) { return 2 * (i * nu + j) + 1; };

  std::unordered_map<long, Vector2d> where;
  // The crossing on the edge from grid point a to grid point b (values on opposite sides).
  const auto cross = [&](long id, long ia, long ja, long ib, long jb) {
    auto it = where.find(id);
    if (it != where.end()) return;
    const Vector2d pa(g.t[ia], g.u[ja]), pb(g.t[ib], g.u[jb]);
    const double va = g.at(ia, ja) - level, vb = g.at(ib, jb) - level;
    double f = std::clamp(va / (va - vb), 0.0, 1.0);
    if (exact) {
      // Bisection keeps the crossing on the edge and matches the field to ~1e-4 of the edge.
      double lo = 0, hi = 1;
      const bool a_high = va >= 0;
      for (int k = 0; k < 14; ++k) {
        const double m = 0.5 * (lo + hi);
        const Vector2d p = pa + m * (pb - pa);
        ((exact(p.x(), p.y()) - level >= 0) == a_high ? lo : hi) = m;
      }
      f = 0.5 * (lo + hi);
    }
    where.emplace(id, pa + f * (pb - pa));
  };

  std::unordered_map<long, long> next;  // segment start crossing -> end crossing
  std::unordered_map<long, int> ends;   // how often a crossing ends a segment
  for (long i = 0; i + 1 < nt; ++i)
    for (long j = 0; j + 1 < nu; ++j) {
      // Corners counter-clockwise in (t, u): (i,j), (i+1,j), (i+1,j+1), (i,j+1); edge k runs
      // from corner k to corner k+1.
      const long ci[4] = {i, i + 1, i + 1, i}, cj[4] = {j, j, j + 1, j + 1};
      const long eid[4] = {h_id(i, j), v_id(i + 1, j), h_id(i, j + 1), v_id(i, j)};
      bool hi[4];
      for (int k = 0; k < 4; ++k) hi[k] = high(ci[k], cj[k]);
      // A crossing where the boundary leaves the high region starts a segment (high on the
      // left), where it enters the high region ends one.
      int starts[2], stops[2], ns = 0, ne = 0;
      int n = 0;
      for (int k = 0; k < 4; ++k) {
        const int k1 = (k + 1) % 4;
        if (hi[k] == hi[k1]) continue;
        cross(eid[k], ci[k], cj[k], ci[k1], cj[k1]);
        ++n;
        if (hi[k])
          starts[ns++] = k;
        else
          stops[ne++] = k;
      }
      if (n == 2) {
        next[eid[starts[0]]] = eid[stops[0]];
        ++ends[eid[stops[0]]];
      } else if (n == 4) {
        const double mean =
            0.25 * (g.at(i, j) + g.at(i + 1, j) + g.at(i + 1, j + 1) + g.at(i, j + 1));
        const bool centre_high = mean >= level;
        // Walking counter-clockwise: a start follows its high corner. Low centre: each start pairs
        // with the end just before it (cutting off the high corner); high centre: with the end just
        // after it (cutting off the low corner).
        for (int a = 0; a < 2; ++a) {
          const int s = starts[a];
          int best = -1;
          for (int b = 0; b < 2; ++b) {
            const int e = stops[b];
            const int dist = centre_high ? (e - s + 4) % 4 : (s - e + 4) % 4;
            if (dist == 1) best = e;
          }
          if (best < 0) best = stops[a];
          next[eid[s]] = eid[best];
          ++ends[eid[best]];
        }
      }
    }

  // Chains: open ones start at crossings that end no segment; the rest are loops.
  std::unordered_map<long, char> used;
  std::vector<long> keys;
  keys.reserve(next.size());
  for (const auto& kv : next) keys.push_back(kv.first);
  std::sort(keys.begin(), keys.end());  // deterministic order
  const auto walk = [&](long first, bool loop) {
    ChartContour c;
    c.closed = loop;
    long id = first;
    while (true) {
      used[id] = 1;
      c.tu.push_back(where.at(id));
      auto it = next.find(id);
      if (it == next.end()) break;
      id = it->second;
      if (id == first) break;
      if (used.count(id)) {
        c.tu.push_back(where.at(id));
        break;
      }
    }
    if (c.tu.size() >= 2) out.push_back(std::move(c));
  };
  for (long k : keys)
    if (!ends.count(k) && !used.count(k)) walk(k, false);
  for (long k : keys)
    if (!used.count(k)) walk(k, true);
  return out;
}

}  // namespace wisp::vector
