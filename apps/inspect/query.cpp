// Picking and the arrangement dump (see inspect_query.hpp).
#include "apps/inspect/query.hpp"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <limits>

#include "vector/band_depth.hpp"
#include "vector/polygon.hpp"

namespace wisp::inspect {
namespace {

using Vec2 = Eigen::Vector2d;

std::string format(const char* fmt, ...) {
  char buf[512];
  va_list args;
  va_start(args, fmt);
  std::vsnprintf(buf, sizeof buf, fmt, args);
  va_end(args);
  return buf;
}

bool face_contains(const vector::ViewFace& f, const Vec2& p) {
  if (f.outer.empty() || !vector::inside_polygon(f.outer, p)) return false;
  for (const auto& hole : f.holes)
    if (!hole.empty() && vector::inside_polygon(hole, p)) return false;
  return true;
}

double segment_distance(const Vec2& a, const Vec2& b, const Vec2& p) {
  const Vec2 d = b - a;
  const double len2 = d.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (a + t * d - p).norm();
}

// The band cells of every wisp of the frame, for depth lookups.
std::vector<vector::BandCells> band_cells(const InspectFrame& f) {
  std::vector<vector::BandCells> out;
  for (const vector::Wisp& w : f.result.wisps) out.push_back(vector::band_cells(w));
  return out;
}

// Covering wisps of a face ordered front to back by their depth at p.
std::vector<std::pair<double, int>> depth_order(const InspectFrame& f,
                                                const std::vector<vector::BandCells>& cells,
                                                const vector::ViewFace& face, const Vec2& p) {
  std::vector<std::pair<double, int>> out;
  for (const auto& [w, winding] : face.cover)
    out.push_back({vector::band_depth(f.result.wisps[w], cells[w], p).depth, w});
  std::sort(out.begin(), out.end());
  return out;
}

std::string wisp_summary(const InspectFrame& f, int w) {
  const vector::Wisp& wisp = f.result.wisps[w];
  double length = 0;
  for (size_t i = 1; i < wisp.sections.size(); ++i)
    length += (wisp.sections[i].centre - wisp.sections[i - 1].centre).norm();
  double hw_min = std::numeric_limits<double>::infinity(), hw_max = 0;
  for (const auto* side : {&wisp.half_width_left, &wisp.half_width_right})
    for (double h : *side) hw_min = std::min(hw_min, h), hw_max = std::max(hw_max, h);
  const auto [zmin, zmax] = std::minmax_element(wisp.centre.depth.begin(), wisp.centre.depth.end());
  const auto& visible = f.result.arrangement.visible[w];
  double shown = 0;
  for (const auto& [s0, s1] : visible) shown += s1 - s0;
  int front = 0;
  for (const vector::ViewFace& face : f.result.arrangement.view.faces)
    front += face.front == w && face.in_view;
  return format(
      "wisp %d: strand %d, samples %d-%d, %d centre spans, %d outline cubics, length %.1f px, "
      "half-width %.2f-%.2f px, depth %.4f-%.4f, outline visible %.0f%% in %d pieces, front in "
      "%d faces",
      w, wisp.strand, wisp.first_sample, wisp.last_sample, wisp.centre.piece_count(),
      wisp.outline.piece_count(), length, std::isfinite(hw_min) ? hw_min : 0.0, hw_max,
      wisp.centre.depth.empty() ? 0.0 : *zmin, wisp.centre.depth.empty() ? 0.0 : *zmax, 100 * shown,
      int(visible.size()), front);
}

nlohmann::json point(const Vec2& p) {
  return {p.x(), p.y()};
}

nlohmann::json ring(const std::vector<Vec2>& r) {
  nlohmann::json out = nlohmann::json::array();
  for (const Vec2& p : r) out.push_back(point(p));
  return out;
}

}  // namespace

int face_at(const vector::ArrangementView& view, const Eigen::Vector2d& p) {
  int unbounded = -1;
  for (size_t i = 0; i < view.faces.size(); ++i) {
    if (view.faces[i].unbounded) unbounded = int(i);
    if (face_contains(view.faces[i], p)) return int(i);
  }
  return unbounded;
}

std::vector<std::string> describe_point(const InspectFrame& f, const Eigen::Vector2d& p) {
  std::vector<std::string> out;
  const vector::ArrangementView& view = f.result.arrangement.view;
  out.push_back(format("frame %d, point (%.2f, %.2f)", f.index, p.x(), p.y()));
  const int fi = face_at(view, p);
  int wisp = -1;
  if (fi < 0) {
    out.push_back("no face (empty arrangement)");
  } else {
    const vector::ViewFace& face = view.faces[fi];
    if (face.cover.empty()) {
      out.push_back(
          format("face %d: %s%s%s", fi, face.base ? "the hair base, no wisp" : "not covered",
                 face.unbounded ? ", unbounded" : "", face.in_view ? "" : ", outside the view"));
    } else {
      // Covered by wisps but no front wisp: an occluder (head, body) is nearer than all of them,
      // and the hair base on the head may show there.
      const std::string front = face.front >= 0 ? format("front-most wisp %d", face.front)
                                : face.base     ? std::string("all behind the head: the hair base")
                                                : std::string("all behind the body (occluder)");
      out.push_back(format("face %d: covered by %d wisp%s, %s%s", fi, int(face.cover.size()),
                           face.cover.size() == 1 ? "" : "s", front.c_str(),
                           face.in_view ? "" : " (outside the view)"));
      for (const auto& [depth, w] : depth_order(f, band_cells(f), face, p)) {
        int winding = 0;
        for (const auto& [cw, n] : face.cover)
          if (cw == w) winding = n;
        out.push_back(format("  wisp %d (strand %d): depth %.5f here, winding %+d%s", w,
                             f.result.wisps[w].strand, depth, winding,
                             w == face.front ? "  <- front" : ""));
      }
      wisp = face.front;
    }
  }

  int best = -1;
  double best_d = std::numeric_limits<double>::infinity();
  for (size_t e = 0; e < view.edges.size(); ++e) {
    const double d = segment_distance(view.edges[e].a, view.edges[e].b, p);
    if (d < best_d) best_d = d, best = int(e);
  }
  if (best >= 0) {
    const vector::ViewEdge& e = view.edges[best];
    out.push_back(format("nearest edge %d, %.2f px away: (%.2f, %.2f) -> (%.2f, %.2f)%s%s", best,
                         best_d, e.a.x(), e.a.y(), e.b.x(), e.b.y(),
                         e.silhouette ? ", silhouette" : "", e.occlusion ? ", occlusion" : ""));
    for (const vector::ViewEdgeSource& s : e.sources) {
      if (s.base) {
        out.push_back(format("  source: the hair base, s %.5f -> %.5f, %s", s.s0, s.s1,
                             s.visible ? "visible" : "hidden"));
        continue;
      }
      if (s.seam) {
        out.push_back(
            "  source: a depth seam (where two wisps, or a wisp and the head or body, "
            "swap depth order)");
        continue;
      }
      if (s.wisp <= -2) {  // occluder k is -2 - k
        out.push_back(
            format("  source: the silhouette of occluder %d (the head or the body)", -2 - s.wisp));
        continue;
      }
      if (s.wisp < 0) {
        out.push_back("  source: a side of the view frame");
        continue;
      }
      if (s.cut) {
        out.push_back(
            format("  source: wisp %d, a cut across its band (its hidden cells beyond "
                   "are left out), hidden",
                   s.wisp));
        if (wisp < 0) wisp = s.wisp;
        continue;
      }
      out.push_back(format("  source: wisp %d, %s side, s %.5f -> %.5f, %s", s.wisp,
                           vector::to_string(s.side), s.s0, s.s1,
                           s.visible ? "visible" : "hidden"));
      if (wisp < 0) wisp = s.wisp;
    }
  }
  if (wisp >= 0) out.push_back(wisp_summary(f, wisp));
  return out;
}

nlohmann::json dump_arrangement(const InspectFrame& f) {
  const render::FrameResult& r = f.result;
  const vector::ArrangementView& view = r.arrangement.view;
  const vector::ArrangementStats& st = r.arrangement.stats;
  nlohmann::json j;
  j["frame"] = f.index;
  j["time"] = f.time;
  j["width"] = f.width();
  j["height"] = f.height();
  j["stats"] = {{"wisps", st.wisps},
                {"segments", st.segments},
                {"vertices", st.vertices},
                {"edges", st.edges},
                {"faces", st.faces},
                {"covered_faces", st.covered_faces},
                {"intersections", st.intersections}};

  nlohmann::json wisps = nlohmann::json::array();
  for (size_t w = 0; w < r.wisps.size(); ++w) {
    const vector::Wisp& wisp = r.wisps[w];
    nlohmann::json visible = nlohmann::json::array();
    for (const auto& [s0, s1] : r.arrangement.visible[w]) visible.push_back({s0, s1});
    wisps.push_back({{"id", w},
                     {"strand", wisp.strand},
                     {"samples", {wisp.first_sample, wisp.last_sample}},
                     {"bounds",
                      {wisp.bounds.min().x(), wisp.bounds.min().y(), wisp.bounds.max().x(),
                       wisp.bounds.max().y()}},
                     {"visible", visible}});
  }
  j["wisps"] = std::move(wisps);

  nlohmann::json faces = nlohmann::json::array();
  const std::vector<vector::BandCells> cells = band_cells(f);
  for (size_t i = 0; i < view.faces.size(); ++i) {
    const vector::ViewFace& face = view.faces[i];
    nlohmann::json cover = nlohmann::json::array(), order = nlohmann::json::array(),
                   holes = nlohmann::json::array();
    for (const auto& [w, n] : face.cover) cover.push_back({{"wisp", w}, {"winding", n}});
    for (const auto& [depth, w] : depth_order(f, cells, face, face.sample))
      order.push_back({{"wisp", w}, {"depth", depth}});
    for (const auto& h : face.holes) holes.push_back(ring(h));
    faces.push_back({{"id", i},
                     {"unbounded", face.unbounded},
                     {"in_view", face.in_view},
                     {"covered", (face.front >= 0 || face.base) && face.in_view},
                     {"base", face.base},
                     {"occluded", face.front < 0 && !face.base && !face.cover.empty()},
                     {"outer", ring(face.outer)},
                     {"holes", std::move(holes)},
                     {"cover", std::move(cover)},
                     {"front", face.front},
                     {"sample", point(face.sample)},
                     {"depth_order", std::move(order)}});
  }
  j["faces"] = std::move(faces);

  nlohmann::json edges = nlohmann::json::array();
  for (size_t i = 0; i < view.edges.size(); ++i) {
    const vector::ViewEdge& e = view.edges[i];
    nlohmann::json sources = nlohmann::json::array();
    for (const vector::ViewEdgeSource& s : e.sources)
      sources.push_back({{"wisp", s.wisp},
                         {"side", s.base         ? "base"
                                  : s.seam       ? "seam"
                                  : s.cut        ? "cut"
                                  : s.wisp <= -2 ? "occluder"
                                  : s.wisp < 0   ? "frame"
                                                 : vector::to_string(s.side)},
                         {"s", {s.s0, s.s1}},
                         {"visible", s.visible}});
    edges.push_back({{"id", i},
                     {"a", point(e.a)},
                     {"b", point(e.b)},
                     {"face_left", e.face_left},
                     {"face_right", e.face_right},
                     {"silhouette", e.silhouette},
                     {"occlusion", e.occlusion},
                     {"sources", std::move(sources)}});
  }
  j["edges"] = std::move(edges);

  nlohmann::json vertices = nlohmann::json::array();
  for (const vector::ViewVertex& v : view.vertices)
    vertices.push_back({{"p", point(v.p)}, {"degree", v.degree}, {"intersection", v.intersection}});
  j["vertices"] = std::move(vertices);
  return j;
}

}  // namespace wisp::inspect
