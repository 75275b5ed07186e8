// arrange_segments (our exact arrangement on snapped input) against CGAL's sweep
// (arrange_segments_cgal): the same faces, each with the same boundary cycles of the same vertices
// and the same sources on every halfedge, compared in a canonical form that ignores numbering.
// Polygons on a small integer grid are the hard cases (shared ends, segments through vertices,
// collinear overlaps, three or more segments through one point, nested components); their
// coordinates are exact in both, so the maps must agree exactly. Wisp outlines are the real input.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "scenes.hpp"
#include "vector/arrangement.hpp"
#include "vector/planar_map.hpp"
#include "vector/wisp.hpp"

using namespace wisp;
using vector::OutlineSegment;
using vector::PlanarMap;

namespace {

// A cycle as text: per halfedge its source vertex (as numbered by `vertex_id`) and its sources
// (segment, runs along it), rotated to start at its smallest halfedge text.
std::string cycle_text(const PlanarMap& m, const std::vector<int>& vertex_id, int h0) {
  std::vector<std::string> items;
  int h = h0;
  do {
    std::ostringstream s;
    s << vertex_id[m.source(h)] << '[';
    const int e = h / 2;
    std::vector<std::pair<int, bool>> src;
    for (int k = m.source_begin[e]; k < m.source_begin[e + 1]; ++k)
      src.push_back({m.sources[k].segment, m.sources[k].along == (h % 2 == 0)});
    std::sort(src.begin(), src.end());
    for (auto [seg, along] : src) s << seg << (along ? '+' : '-');
    s << ']';
    items.push_back(s.str());
    h = m.halfedges[h].next;
  } while (h != h0);
  std::rotate(items.begin(), std::min_element(items.begin(), items.end()), items.end());
  std::string out;
  for (const std::string& i : items) out += i + ' ';
  return out;
}

// The map as sorted face texts: outer cycle (none for the unbounded face), then sorted holes.
// Checks on the way that every halfedge's face is the face whose cycles hold it.
std::vector<std::string> canonical(const PlanarMap& m, const std::vector<int>& vertex_id) {
  std::vector<std::string> faces;
  for (int f = 0; f < int(m.faces.size()); ++f) {
    const PlanarMap::Face& face = m.faces[f];
    auto check_faces = [&](int h0) {
      int h = h0;
      do {
        REQUIRE(m.halfedges[h].face == f);
        h = m.halfedges[h].next;
      } while (h != h0);
    };
    std::string text = f == m.unbounded_face ? "unbounded" : cycle_text(m, vertex_id, face.outer);
    if (face.outer >= 0) check_faces(face.outer);
    std::vector<std::string> holes;
    for (int k = face.holes_begin; k < face.holes_end; ++k) {
      holes.push_back(cycle_text(m, vertex_id, m.holes[k]));
      check_faces(m.holes[k]);
    }
    std::sort(holes.begin(), holes.end());
    for (const std::string& hole : holes) text += " | " + hole;
    faces.push_back(text);
  }
  std::sort(faces.begin(), faces.end());
  return faces;
}

// Our vertices numbered as CGAL's: each matched to the nearest of CGAL's, within `tolerance`,
// and no two to the same.
std::vector<int> match_vertices(const PlanarMap& ours, const PlanarMap& cgal, double tolerance) {
  std::vector<std::pair<double, int>> by_x;
  for (int v = 0; v < int(cgal.vertices.size()); ++v) by_x.push_back({cgal.vertices[v].x(), v});
  std::sort(by_x.begin(), by_x.end());
  std::vector<int> id;
  std::vector<char> taken(cgal.vertices.size(), 0);
  for (const Eigen::Vector2d& p : ours.vertices) {
    int found = -1;
    double nearest = INFINITY;
    for (auto it =
             std::lower_bound(by_x.begin(), by_x.end(), std::make_pair(p.x() - tolerance, -1));
         it != by_x.end() && it->first <= p.x() + tolerance; ++it) {
      const double d = (cgal.vertices[it->second] - p).norm();
      if (d <= tolerance && d < nearest) found = it->second, nearest = d;
    }
    INFO("vertex " << p.transpose());
    REQUIRE(found >= 0);
    REQUIRE(!taken[found]);
    taken[found] = 1;
    id.push_back(found);
  }
  return id;
}

// The same map up to numbering; vertices within `tolerance` (ours are snapped to a grid).
void require_same_as_cgal(const std::vector<OutlineSegment>& segments, double tolerance) {
  const PlanarMap ours = vector::arrange_segments(segments);
  const PlanarMap cgal = vector::arrange_segments_cgal(segments);
  REQUIRE(ours.vertices.size() == cgal.vertices.size());
  REQUIRE(ours.edge_count() == cgal.edge_count());
  REQUIRE(ours.faces.size() == cgal.faces.size());
  REQUIRE(ours.holes.size() == cgal.holes.size());
  std::vector<int> identity(cgal.vertices.size());
  for (int v = 0; v < int(identity.size()); ++v) identity[v] = v;
  REQUIRE(canonical(ours, match_vertices(ours, cgal, tolerance)) == canonical(cgal, identity));
}

// `count` closed polygons of 3-6 corners on the integer grid [0, size]^2.
std::vector<OutlineSegment> grid_polygons(int count, int size, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> coord(0, size), corners(3, 6);
  std::vector<OutlineSegment> out;
  for (int k = 0; k < count; ++k) {
    std::vector<Eigen::Vector2d> ring(corners(rng));
    for (auto& p : ring) p = Eigen::Vector2d(coord(rng), coord(rng));
    for (size_t i = 0; i < ring.size(); ++i)
      out.push_back({ring[i], ring[(i + 1) % ring.size()], k});
  }
  return out;
}

OutlineSegment side(double ax, double ay, double bx, double by) {
  return {Eigen::Vector2d(ax, ay), Eigen::Vector2d(bx, by)};
}

}  // namespace

TEST_CASE("degenerate polygons on a small grid arrange as CGAL arranges them",
          "[vector][arrangement]") {
  // Grid 4: nearly every segment shares ends, overlaps or passes through vertices of others.
  for (std::uint32_t seed = 1; seed <= 60; ++seed) {
    INFO("seed " << seed);
    require_same_as_cgal(grid_polygons(1 + seed % 7, seed % 3 == 0 ? 4 : 12, seed), 1e-9);
  }
}

TEST_CASE("steep and long segments meet everything they cross", "[vector][arrangement]") {
  // Nearly vertical needles and nearly horizontal bars across the whole candidate grid: each is
  // registered in hundreds of cells, its y range per column from its slope.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> pos(0, 1000), lean(-1e-3, 1e-3);
  std::vector<OutlineSegment> s;
  for (int k = 0; k < 40; ++k) {
    const double x = pos(rng), y = pos(rng);
    s.push_back(side(x, -10, x + lean(rng), 1010));
    s.push_back(side(-10, y, 1010, y + lean(rng)));
  }
  require_same_as_cgal(s, 1e-5);  // the snap is 2^-19 px here
}

TEST_CASE("nested components find the face they lie in", "[vector][arrangement]") {
  std::vector<OutlineSegment> s;
  auto square = [&](double lo, double hi) {
    s.push_back(side(lo, lo, hi, lo));
    s.push_back(side(hi, lo, hi, hi));
    s.push_back(side(hi, hi, lo, hi));
    s.push_back(side(lo, hi, lo, lo));
  };
  square(0, 100);
  square(10, 90);  // a hole in the first square's face
  square(20, 30);  // two holes side by side in the second's
  s.push_back(side(60, 20, 80, 20));
  s.push_back(side(80, 20, 70, 40));
  s.push_back(side(70, 40, 60, 20));
  s.push_back(side(67, 25, 73, 25));    // a lone segment inside the triangle...
  s.push_back(side(0, 50, -20, 50));    // ...and an antenna on the outside, along the ray
  s.push_back(side(-30, 50, -25, 50));  // a segment met by the ray at its end
  s.push_back(side(-40, 40, -40, 60));  // and one met inside
  require_same_as_cgal(s, 1e-9);
  const PlanarMap ours = vector::arrange_segments(s);
  // The unbounded face holds the outer square with its antenna, and the two lone segments.
  CHECK(ours.faces[ours.unbounded_face].holes_end - ours.faces[ours.unbounded_face].holes_begin ==
        3);
}

TEST_CASE("wisp outlines arrange as CGAL arranges them", "[vector][arrangement]") {
  vector::WispStyle style;
  for (std::uint32_t seed : {3u, 11u}) {
    std::vector<OutlineSegment> segments;
    const auto wisps = vector::build_wisps(test::random_frame(40, seed), style);
    for (int w = 0; w < int(wisps.size()); ++w) {
      const auto poly = vector::outline_polygon(wisps[w]);
      for (size_t i = 0; i < poly.size(); ++i)
        segments.push_back({poly[i].p, poly[(i + 1) % poly.size()].p, w});
    }
    for (const OutlineSegment& frame :
         {side(0, 0, 512, 0), side(512, 0, 512, 512), side(512, 512, 0, 512), side(0, 512, 0, 0)})
      segments.push_back(frame);
    INFO("seed " << seed << ", " << segments.size() << " segments");
    require_same_as_cgal(segments, 1e-3);
  }
}

TEST_CASE("arrange_segments names a non-finite segment", "[vector][arrangement]") {
  std::vector<OutlineSegment> s = {side(0, 0, 1, 0), side(1, 0, NAN, 1)};
  CHECK_THROWS_WITH(vector::arrange_segments(s), "arrangement: segment 1 is not finite");
  const PlanarMap empty = vector::arrange_segments({side(2, 2, 2, 2)});
  CHECK(empty.faces.size() == 1);
  CHECK(empty.edge_count() == 0);
}
