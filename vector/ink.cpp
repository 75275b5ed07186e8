// Hair mask cycles and ink polylines on the plain planar map.
#include "vector/ink.hpp"

#include <algorithm>
#include <numeric>

#include "vector/polygon.hpp"

namespace wisp::vector {

using Eigen::Vector2d;

std::vector<HairMask> trace_regions(const PlanarMap& map, const std::vector<int>& label,
                                    int labels) {
  const auto& he = map.halfedges;
  const auto lab = [&](int h) { return label[he[h].face]; };
  auto boundary = [&](int h) { return lab(h) >= 0 && lab(h) != lab(h ^ 1); };

  // Connected regions: faces joined across edges with the same label on both sides.
  std::vector<int> region(map.faces.size(), -1), region_label;
  std::vector<int> stack;
  // Each face's halfedges in index order: face f's are at[first[f] .. first[f + 1]).
  std::vector<int> first(map.faces.size() + 1, 0), at(he.size());
  for (const auto& x : he) ++first[x.face + 1];
  for (size_t f = 0; f < map.faces.size(); ++f) first[f + 1] += first[f];
  {
    std::vector<int> fill(first.begin(), first.end() - 1);
    for (int h = 0; h < int(he.size()); ++h) at[fill[he[h].face]++] = h;
  }
  for (int f = 0; f < int(map.faces.size()); ++f) {
    if (label[f] < 0 || region[f] >= 0) continue;
    region[f] = int(region_label.size());
    stack = {f};
    while (!stack.empty()) {
      const int g = stack.back();
      stack.pop_back();
      for (int i = first[g]; i < first[g + 1]; ++i) {
        const int n = he[at[i] ^ 1].face;
        if (label[n] == label[f] && region[n] < 0) region[n] = region[f], stack.push_back(n);
      }
    }
    region_label.push_back(label[f]);
  }

  // Boundary cycles: from a boundary halfedge, the next one turns around its target through faces
  // of the same label until it leaves them again, so each cycle stays in one region.
  struct Cycle {
    std::vector<Vector2d> ring;
    double area;
  };
  std::vector<std::vector<Cycle>> cycles(region_label.size());
  std::vector<char> used(he.size(), 0);
  for (int h0 = 0; h0 < int(he.size()); ++h0) {
    if (used[h0] || !boundary(h0)) continue;
    Cycle c;
    int h = h0;
    do {
      used[h] = 1;
      c.ring.push_back(map.vertices[map.source(h)]);
      int g = he[h].next;
      while (!boundary(g)) g = he[g ^ 1].next;
      h = g;
    } while (h != h0 && !used[h]);
    c.area = signed_area(c.ring);
    cycles[region[he[h0].face]].push_back(std::move(c));
  }

  std::vector<HairMask> masks(labels);
  for (size_t r = 0; r < cycles.size(); ++r) {
    auto& rc = cycles[r];
    if (rc.empty()) continue;
    std::vector<MaskPolygon>& polygons = masks[region_label[r]].polygons;
    // The outer boundary turns counter-clockwise (positive area); in a region that touches itself
    // at a vertex there may be more than one, the largest takes the holes.
    std::sort(rc.begin(), rc.end(), [](const Cycle& a, const Cycle& b) { return a.area > b.area; });
    const size_t first_polygon = polygons.size();
    for (auto& c : rc) {
      if (c.area > 0)
        polygons.push_back({std::move(c.ring), {}});
      else if (polygons.size() > first_polygon)
        polygons[first_polygon].holes.push_back(std::move(c.ring));
    }
  }
  return masks;
}

HairMask trace_hair_mask(const PlanarMap& map, const std::vector<char>& hair) {
  std::vector<int> label(hair.size());
  for (size_t f = 0; f < hair.size(); ++f) label[f] = hair[f] ? 0 : -1;
  return std::move(trace_regions(map, label, 1)[0]);
}

std::vector<InkLine> chain_edges(const PlanarMap& map, const std::vector<int>& owner) {
  const int edges = map.edge_count();
  std::vector<std::vector<int>> at(map.vertices.size());  // selected halfedges leaving a vertex
  for (int e = 0; e < edges; ++e) {
    if (owner[e] < 0) continue;
    at[map.source(2 * e)].push_back(2 * e);
    at[map.source(2 * e + 1)].push_back(2 * e + 1);
  }
  auto pass_through = [&](int v) {
    return at[v].size() == 2 && owner[at[v][0] / 2] == owner[at[v][1] / 2];
  };
  std::vector<char> used(edges, 0);
  std::vector<InkLine> lines;
  auto walk = [&](int h) {
    InkLine line;
    line.wisp = owner[h / 2];
    line.points.push_back(map.vertices[map.source(h)]);
    while (true) {
      used[h / 2] = 1;
      const int v = map.halfedges[h].target;
      line.points.push_back(map.vertices[v]);
      if (!pass_through(v)) break;
      const int next = at[v][0] / 2 == h / 2 ? at[v][1] : at[v][0];
      if (used[next / 2]) {
        line.closed = true;
        line.points.pop_back();
        break;
      }
      h = next;
    }
    lines.push_back(std::move(line));
  };
  // Open chains start where the chaining stops; what is left are closed loops.
  for (int v = 0; v < int(at.size()); ++v)
    if (!pass_through(v))
      for (int h : at[v])
        if (!used[h / 2]) walk(h);
  for (int e = 0; e < edges; ++e)
    if (owner[e] >= 0 && !used[e]) walk(2 * e);
  return lines;
}

}  // namespace wisp::vector
