// Hatch lines on the body's surfaces (see body_hatching.hpp).
#include "apps/render/body_hatching.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <tuple>

#include "vector/hatching.hpp"
#include "vector/ink_strokes.hpp"
#include "vector/stroke_fit.hpp"
#include "vector/visible_region.hpp"

namespace wisp::render {
namespace {

using Eigen::Vector2d;

constexpr double kSampleStep = 1.0;     // px between the samples of a line
constexpr double kFitTolerance = 0.05;  // px

// One surface's front triangles where it shows past the solids drawn before it, binned by rows
// and columns for point queries.
class SurfaceCover {
 public:
  explicit SurfaceCover(const sim::ProjectedSurface& s) : s_(s) {
    for (const Eigen::Vector3i& t : s.triangles)
      for (int k = 0; k < 3; ++k) box_.extend(s.pixel[t[k]]);
    if (box_.isEmpty()) return;
    cols_ = std::max(1, int(std::ceil(box_.sizes().x() / kBin)));
    rows_ = std::max(1, int(std::ceil(box_.sizes().y() / kBin)));
    bins_.resize(size_t(cols_) * rows_);
    for (int i = 0; i < int(s.triangles.size()); ++i) {
      Eigen::AlignedBox2d b;
      for (int k = 0; k < 3; ++k) b.extend(s.pixel[s.triangles[i][k]]);
      const auto [c0, r0] = cell(b.min());
      const auto [c1, r1] = cell(b.max());
      for (int r = r0; r <= r1; ++r)
        for (int c = c0; c <= c1; ++c) bins_[size_t(r) * cols_ + c].push_back(i);
    }
  }

  bool covers(const Vector2d& p) const {
    if (bins_.empty() || !box_.contains(p)) return false;
    const auto [c, r] = cell(p);
    for (int i : bins_[size_t(r) * cols_ + c]) {
      const Eigen::Vector3i& t = s_.triangles[i];
      const Vector2d a = s_.pixel[t[0]], e1 = s_.pixel[t[1]] - a, e2 = s_.pixel[t[2]] - a;
      const double det = e1.x() * e2.y() - e1.y() * e2.x();
      if (std::abs(det) < 1e-12) continue;
      const Vector2d d = p - a;
      const double w1 = (d.x() * e2.y() - d.y() * e2.x()) / det;
      const double w2 = (e1.x() * d.y() - e1.y() * d.x()) / det;
      const double w0 = 1 - w1 - w2;
      if (w0 < 0 || w1 < 0 || w2 < 0) continue;
      const auto c_at = [&](int k) { return std::min(double(s_.clearance[t[k]]), 1e6); };
      if (w0 * c_at(0) + w1 * c_at(1) + w2 * c_at(2) >= 0) return true;
    }
    return false;
  }

 private:
  static constexpr double kBin = 8;  // px
  std::pair<int, int> cell(const Vector2d& p) const {
    return {std::clamp(int((p.x() - box_.min().x()) / kBin), 0, cols_ - 1),
            std::clamp(int((p.y() - box_.min().y()) / kBin), 0, rows_ - 1)};
  }
  const sim::ProjectedSurface& s_;
  Eigen::AlignedBox2d box_;
  int cols_ = 0, rows_ = 0;
  std::vector<std::vector<int>> bins_;
};

// Where each surface of the body shows, and the hair over it.
class BodyView {
 public:
  BodyView(const sim::ProjectedBody& body, const vector::HairMask& hair, int width, int height)
      : view_(vector::image_rect(width, height)), hair_(mask_view(hair), 1) {
    for (const sim::ProjectedSurface& s : body.surfaces) covers_.emplace_back(s);
  }
  bool shows(int s, const Vector2d& p) const {
    if (!covers_[s].covers(p)) return false;
    for (size_t j = s + 1; j < covers_.size(); ++j)
      if (covers_[j].covers(p)) return false;
    return true;
  }
  bool shows_skin(int s, const Vector2d& p) const {
    return view_.contains(p) && !hair_.contains(0, p) && shows(s, p);
  }
  // Whether the hair mask's boundary crosses segment a-b (a thin tip between two samples).
  bool hair_crosses(const Vector2d& a, const Vector2d& b) const { return hair_.crosses(0, a, b); }

 private:
  // The mask as the faces of one "wisp", for VisibleRegions' point test (even-odd over rings).
  static vector::ArrangementView mask_view(const vector::HairMask& hair) {
    vector::ArrangementView v;
    for (const vector::MaskPolygon& m : hair.polygons) {
      vector::ViewFace f;
      f.outer = m.outer;
      f.holes = m.holes;
      f.front = 0;
      f.in_view = true;
      v.faces.push_back(std::move(f));
    }
    return v;
  }
  Eigen::AlignedBox2d view_;
  vector::VisibleRegions hair_;
  std::vector<SurfaceCover> covers_;
};

// A point of a line: in pixels, with the surface's shade and clearance there.
struct Node {
  Vector2d p{0, 0};
  double shade = 1, clearance = 0;
};
Node mix(const Node& a, const Node& b, double f) {
  return {a.p + f * (b.p - a.p), a.shade + f * (b.shade - a.shade),
          a.clearance + f * (b.clearance - a.clearance)};
}

// The level sets field = i (integers i) of one family on one surface, chained into polylines:
// per level, the crossings of its mesh edges (keyed by the edge, so the two triangles of an edge
// share the point) joined across each triangle.
std::map<long, std::vector<std::vector<Node>>> level_lines(
    const sim::ProjectedSurface& s, const std::vector<double>& field,
    const std::function<double(long)>& tone) {
  using Key = std::tuple<int, int, long>;  // edge (i < j), level
  std::map<Key, Node> point;
  std::map<Key, std::vector<Key>> next;  // the crossings a crossing is joined to
  for (const Eigen::Vector3i& t : s.triangles) {
    double lo = 1e300, hi = -1e300, dark = 1e300;
    for (int k = 0; k < 3; ++k) {
      lo = std::min(lo, field[t[k]]), hi = std::max(hi, field[t[k]]);
      dark = std::min(dark, double(s.shade[t[k]]));
    }
    for (long i = long(std::ceil(lo)); i <= long(std::floor(hi)); ++i) {
      if (!(dark < tone(i))) continue;  // the line's band never shows in this triangle
      std::vector<Key> ends;
      for (int k = 0; k < 3; ++k) {
        int a = t[k], b = t[(k + 1) % 3];
        if (a > b) std::swap(a, b);
        // Off the level by a hair, so a vertex on it counts on one side (as in body_paths).
        const auto g = [&](int v) {
          const double d = field[v] - double(i);
          return std::abs(d) < 1e-9 ? 1e-9 : d;
        };
        if ((g(a) > 0) == (g(b) > 0)) continue;
        const double f = g(a) / (g(a) - g(b));
        const Key key{a, b, i};
        const Node na{s.pixel[a], s.shade[a], std::min(double(s.clearance[a]), 1e6)};
        const Node nb{s.pixel[b], s.shade[b], std::min(double(s.clearance[b]), 1e6)};
        point.emplace(key, mix(na, nb, f));
        ends.push_back(key);
      }
      if (ends.size() != 2) continue;
      next[ends[0]].push_back(ends[1]);
      next[ends[1]].push_back(ends[0]);
    }
  }
  std::map<long, std::vector<std::vector<Node>>> out;
  std::map<Key, bool> used;
  const auto walk = [&](Key start) {
    std::vector<Node> line{point.at(start)};
    used[start] = true;
    Key at = start;
    for (;;) {
      const auto it = next.find(at);
      Key to = at;
      bool found = false;
      for (const Key& k : it->second)
        if (!used[k]) to = k, found = true;
      if (!found) break;
      used[to] = true;
      line.push_back(point.at(to));
      at = to;
    }
    out[std::get<2>(start)].push_back(std::move(line));
  };
  for (const auto& [key, links] : next)  // open lines from their ends first
    if (links.size() == 1 && !used[key]) walk(key);
  for (const auto& [key, links] : next)  // then the loops
    if (!used[key]) walk(key);
  return out;
}

double smoothstep(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3 - 2 * x);
}

}  // namespace

std::vector<bool> body_surface_shows(const sim::ProjectedBody& body, int s,
                                     const std::vector<Vector2d>& points) {
  const BodyView view(body, {}, 1, 1);
  std::vector<bool> out;
  for (const Vector2d& p : points) out.push_back(view.shows(s, p));
  return out;
}

std::vector<BodyHatch> hatch_body(const sim::ProjectedBody& body, const vector::HairMask& hair,
                                  const vector::HairStyle& style, int width, int height) {
  std::vector<BodyHatch> out;
  const vector::HatchStyle& st = style.hatching;
  if (!st.enabled || !st.body || body.surfaces.empty()) return out;
  const BodyView view(body, hair, width, height);
  const double scale = vector::ink_scale(style.ink, width, height);
  const double full = st.width * scale, taper = st.end_taper * scale;
  const int bands = int(st.body_tones.size());
  const bool cross = st.cross && bands >= 2;
  const int along_bands = cross ? bands - 1 : bands;
  const double angle = st.cross_angle_deg * M_PI / 180;
  for (int si = 0; si < int(body.surfaces.size()); ++si) {
    const sim::ProjectedSurface& s = body.surfaces[si];
    if (s.local.size() != s.pixel.size()) continue;
    for (bool is_cross : {false, true}) {
      if (is_cross && !cross) continue;
      std::vector<double> field(s.local.size());
      for (size_t v = 0; v < field.size(); ++v) {
        const Eigen::Vector3d& q = s.local[v];
        field[v] = (is_cross ? q.y() * std::cos(angle) + q.x() * std::sin(angle) : q.y()) /
                   st.body_spacing;
      }
      // The band of line i: the cross family is the darkest band; in the along family the
      // lightest band whose spacing divides i.
      const auto band_of = [&](long i) {
        if (is_cross) return bands - 1;
        for (int k = 0; k < along_bands; ++k)
          if (i % (1L << (along_bands - 1 - k)) == 0) return k;
        return along_bands - 1;
      };
      const auto tone = [&](long i) { return st.body_tones[band_of(i)]; };
      for (const auto& [level, lines] : level_lines(s, field, tone)) {
        const int band = band_of(level);
        const double t = st.body_tones[band];
        for (const std::vector<Node>& line : lines) {
          // Samples at most kSampleStep apart, each with whether it shows.
          struct Sample {
            Node n;
            bool on = false;
          };
          const auto on = [&](const Node& n) {
            return n.clearance >= 0 && n.shade < t && view.shows_skin(si, n.p);
          };
          std::vector<Sample> samples;
          for (size_t k = 0; k + 1 < line.size(); ++k) {
            const int m =
                std::max(1, int(std::ceil((line[k + 1].p - line[k].p).norm() / kSampleStep)));
            for (int j = 0; j < m; ++j) {
              const Node n = mix(line[k], line[k + 1], double(j) / m);
              samples.push_back({n, on(n)});
            }
          }
          if (!line.empty()) samples.push_back({line.back(), on(line.back())});
          const auto between = [&](const Sample& a, const Sample& b, double m) {
            const Node n = mix(a.n, b.n, m);
            return Sample{n, on(n)};
          };
          // A tip of hair may cross between two samples that show skin.
          const auto crosses = [&](const Sample& a, const Sample& b) {
            return (b.n.p - a.n.p).norm() >= 1e-3 && view.hair_crosses(a.n.p, b.n.p);
          };
          const auto edge_iterations = [](const Sample& a, const Sample& b) {
            return std::clamp(
                int(std::ceil(std::log2(std::max(1.0, (b.n.p - a.n.p).norm() / 1e-4)))), 1, 30);
          };
          for (const std::vector<Sample>& run :
               vector::runs_on(samples, between, crosses, edge_iterations)) {
            std::vector<Vector2d> pts;
            std::vector<double> arc = {0};
            for (const Sample& r : run) {
              if (!pts.empty()) arc.push_back(arc.back() + (r.n.p - pts.back()).norm());
              pts.push_back(r.n.p);
            }
            const double len = arc.back();
            if (len < 1) continue;
            vector::FitOptions fit;
            fit.tolerance = kFitTolerance;
            const vector::FittedPath path = vector::fit_cubics(pts, fit);
            if (path.piece_count() == 0) continue;
            std::vector<std::pair<double, double>> widths;
            for (size_t k = 0; k < run.size(); ++k) {
              double w = full * vector::tone_gate(run[k].n.shade, t, st.soft);
              if (taper > 0) w *= smoothstep(arc[k] / taper) * smoothstep((len - arc[k]) / taper);
              widths.emplace_back(path.param[k], w);
            }
            BodyHatch h;
            h.stroke = ink_stroke(path, widths, st.color);
            h.surface = si;
            h.band = band;
            h.cross = is_cross;
            h.level = level * st.body_spacing;
            out.push_back(std::move(h));
          }
        }
      }
    }
  }
  return out;
}

}  // namespace wisp::render
