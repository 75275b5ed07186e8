// Scene JSON reader: see scene.hpp. Each part is a small function over a field reader that
// remembers which keys it consumed, so whatever is left over is an unknown field, reported with
// the nearest known name when it looks like a typo.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/ramp_file.hpp"
#include "io/scene.hpp"

namespace wisp::io {
namespace {

using nlohmann::json;

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] != b[j - 1])});
      diag = up;
    }
  }
  return row[b.size()];
}

// Reads the fields of one JSON object; `where` is the dotted path used in messages ("hair").
class Fields {
 public:
  Fields(const json& obj, std::string where, std::string file)
      : obj_(obj), where_(std::move(where)), file_(std::move(file)) {
    if (!obj_.is_object()) fail(where_, "expected an object");
  }

  [[noreturn]] void fail(const std::string& field, const std::string& what) const {
    throw std::invalid_argument(file_ + ": " + field + ": " + what);
  }
  std::string name(const char* key) const { return where_.empty() ? key : where_ + "." + key; }

  // The raw value of `key`, or null if absent; marks the key as known.
  const json* find(const char* key) {
    known_.insert(key);
    const auto it = obj_.find(key);
    return it == obj_.end() ? nullptr : &*it;
  }

  void get(const char* key, double& out) {
    if (const json* v = find(key)) out = number(*v, name(key));
  }
  void get(const char* key, int& out) {
    if (const json* v = find(key)) {
      if (!v->is_number_integer()) fail(name(key), "expected an integer, got " + v->dump());
      const auto n = v->get<long long>();
      if (n < -1000000000LL || n > 1000000000LL) fail(name(key), "out of range");
      out = static_cast<int>(n);
    }
  }
  void get(const char* key, std::uint64_t& out) {
    if (const json* v = find(key)) {
      if (!v->is_number_unsigned())
        fail(name(key), "expected a non-negative integer, got " + v->dump());
      out = v->get<std::uint64_t>();
    }
  }
  void get(const char* key, bool& out) {
    if (const json* v = find(key)) {
      if (!v->is_boolean()) fail(name(key), "expected true or false, got " + v->dump());
      out = v->get<bool>();
    }
  }
  void get(const char* key, std::string& out) {
    if (const json* v = find(key)) {
      if (!v->is_string()) fail(name(key), "expected a string, got " + v->dump());
      out = v->get<std::string>();
    }
  }
  void get(const char* key, Eigen::Vector3d& out) {
    if (const json* v = find(key)) out = vector3(*v, name(key));
  }
  // An RGB colour: [r, g, b] with every component in [0, 1].
  void color(const char* key, Eigen::Vector3f& out) {
    if (const json* v = find(key)) {
      const Eigen::Vector3d c = vector3(*v, name(key));
      if (c.minCoeff() < 0 || c.maxCoeff() > 1)
        fail(name(key), "colour components must be in [0, 1], got " + v->dump());
      out = c.cast<float>();
    }
  }
  // One of `choices`.
  void choice(const char* key, std::string& out, const std::vector<std::string>& choices) {
    get(key, out);
    for (const auto& c : choices)
      if (c == out) return;
    std::string list;
    for (const auto& c : choices) list += (list.empty() ? "" : ", ") + c;
    fail(name(key), "expected one of " + list + ", got \"" + out + "\"" + suggest(out, choices));
  }

  double number(const json& v, const std::string& field) const {
    if (!v.is_number()) fail(field, "expected a number, got " + v.dump());
    const double d = v.get<double>();
    if (!std::isfinite(d)) fail(field, "not a finite number");
    return d;
  }
  Eigen::Vector3d vector3(const json& v, const std::string& field) const {
    if (!v.is_array() || v.size() != 3)
      fail(field, "expected an array of 3 numbers, got " + v.dump());
    return {number(v[0], field + "[0]"), number(v[1], field + "[1]"), number(v[2], field + "[2]")};
  }

  // Fails on the first key that no get() asked for.
  void finish() const {
    for (auto it = obj_.begin(); it != obj_.end(); ++it)
      if (!known_.count(it.key()))
        fail(name(it.key().c_str()),
             "unknown field" +
                 suggest(it.key(), std::vector<std::string>(known_.begin(), known_.end())));
  }

  static std::string suggest(const std::string& key, const std::vector<std::string>& known) {
    std::string best;
    std::size_t best_d = std::max<std::size_t>(2, key.size() / 3) + 1;
    for (const auto& k : known) {
      const std::size_t d = edit_distance(key, k);
      if (d < best_d) {
        best_d = d;
        best = k;
      }
    }
    return best.empty() ? "" : " (did you mean \"" + best + "\"?)";
  }

  const std::string& file() const { return file_; }

 private:
  const json& obj_;
  std::string where_, file_;
  std::set<std::string> known_;
};

void require(Fields& f, bool ok, const char* key, const std::string& what) {
  if (!ok) f.fail(f.name(key), what);
}

std::filesystem::path resolve(const std::filesystem::path& scene, const std::string& file) {
  const std::filesystem::path p(file);
  return p.is_absolute() ? p : scene.parent_path() / p;
}

void parse_head(Fields& f, Scene& s) {
  sim::HeadParams& h = s.head;
  f.choice("shape", h.shape, {"ellipsoid", "mesh"});
  f.get("radii", h.radii);
  require(f, h.radii.minCoeff() > 0, "radii", "every radius must be positive");
  std::string mesh;
  f.get("mesh", mesh);
  if (!mesh.empty()) h.mesh = resolve(s.path, mesh);
  require(f, h.shape != "mesh" || !mesh.empty(), "mesh", "shape \"mesh\" needs an OBJ file name");
  f.get("mesh_scale", h.mesh_scale);
  require(f, h.mesh_scale > 0, "mesh_scale", "must be positive");
  f.get("mesh_offset", h.mesh_offset);
  f.get("shoulders", h.shoulders);
  f.get("shoulder_center", h.shoulder_center);
  f.get("shoulder_half_width", h.shoulder_half_width);
  require(f, h.shoulder_half_width >= 0, "shoulder_half_width", "must be >= 0");
  f.get("shoulder_radius", h.shoulder_radius);
  require(f, h.shoulder_radius > 0, "shoulder_radius", "must be positive");
}

void parse_hair(Fields& f, Scene& s) {
  sim::HairParams& h = s.hair;
  f.choice("source", h.source, {"procedural", "json", "hair"});
  std::string file;
  f.get("file", file);
  if (!file.empty()) h.file = resolve(s.path, file);
  require(f, h.source == "procedural" || !file.empty(), "file",
          "source \"" + h.source + "\" needs a strand file name");
  f.get("count", h.count);
  require(f, h.source == "procedural" ? h.count >= 1 : h.count >= 0, "count",
          "must be " +
              std::string(h.source == "procedural" ? "at least 1" : ">= 0 (0 = all strands)") +
              ", got " + std::to_string(h.count));
  require(f, h.count <= 100000, "count", "at most 100000 guides");
  f.get("segments", h.segments);
  require(f, h.source == "procedural" ? h.segments >= 1 : h.segments >= 0, "segments",
          "must be at least 1 (0 keeps a file's points), got " + std::to_string(h.segments));
  require(f, h.segments <= 1000, "segments", "at most 1000");
  f.get("length", h.length);
  require(f, h.length > 0, "length", "must be a positive length in metres");
  f.get("length_variation", h.length_variation);
  require(f, h.length_variation >= 0 && h.length_variation < 1, "length_variation",
          "must be in [0, 1)");
  f.choice("style", h.style, {"straight", "wavy", "curly"});
  f.get("amplitude", h.amplitude);
  require(f, h.amplitude >= 0, "amplitude", "must be >= 0");
  f.get("frequency", h.frequency);
  require(f, h.frequency >= 0, "frequency", "must be >= 0");
  f.get("parting_deg", h.parting_deg);
  f.get("comb", h.comb);
  require(f, h.comb >= 0, "comb", "must be >= 0");
  f.get("scalp_angle_deg", h.scalp_angle_deg);
  require(f, h.scalp_angle_deg > 0 && h.scalp_angle_deg <= 180, "scalp_angle_deg",
          "must be in (0, 180]");
  f.get("face_angle_deg", h.face_angle_deg);
  require(f, h.face_angle_deg >= 0 && h.face_angle_deg < 180, "face_angle_deg",
          "must be in [0, 180)");
  f.get("seed", h.seed);
  f.get("file_scale", h.file_scale);
  require(f, h.file_scale > 0, "file_scale", "must be positive");
  f.get("file_offset", h.file_offset);
  f.get("file_z_up", h.file_z_up);
}

void parse_motion(Fields& f, Scene& s) {
  sim::MotionParams& m = s.motion;
  f.choice("preset", m.preset, {"none", "turn", "nod", "shake", "walk", "keys"});
  f.get("duration", m.duration);
  require(f, m.duration > 0 && m.duration <= 3600, "duration", "must be in (0, 3600] seconds");
  f.get("amplitude", m.amplitude);
  f.get("speed", m.speed);
  require(f, m.speed > 0, "speed", "must be positive");
  f.get("settle", m.settle);
  require(f, m.settle >= 0, "settle", "must be >= 0");
  if (const json* keys = f.find("keys")) {
    if (!keys->is_array()) f.fail("motion.keys", "expected an array of keyframes");
    for (std::size_t i = 0; i < keys->size(); ++i) {
      Fields k((*keys)[i], "motion.keys[" + std::to_string(i) + "]", f.file());
      sim::Keyframe key;
      k.get("time", key.time);
      k.get("position", key.position);
      k.get("ypr_deg", key.ypr_deg);
      k.finish();
      if (i > 0 && !(key.time > m.keys.back().time))
        k.fail(k.name("time"), "keyframe times must increase");
      m.keys.push_back(key);
    }
  }
  require(f, m.preset != "keys" || !m.keys.empty(), "keys",
          "preset \"keys\" needs at least one keyframe");
}

void parse_sim(Fields& f, Scene& s) {
  sim::SimParams& p = s.sim;
  f.choice("model", p.model, {"dftl", "featherstone", "rope"});
  f.get("fps", p.fps);
  require(f, p.fps > 0 && p.fps <= 1000, "fps", "must be in (0, 1000]");
  f.get("step_rate", p.step_rate);
  require(f, p.step_rate >= p.fps && p.step_rate <= 100000, "step_rate",
          "must be in [sim.fps, 100000] Hz");
  f.get("substeps", p.substeps);
  require(f, p.substeps >= 1 && p.substeps <= 1000, "substeps", "must be in [1, 1000]");
  f.get("iterations", p.iterations);
  require(f, p.iterations >= 1 && p.iterations <= 1000, "iterations", "must be in [1, 1000]");
  f.get("gravity", p.gravity);
  f.get("density", p.density);
  require(f, p.density > 0, "density", "must be positive (kg/m)");
  f.get("bend_stiffness", p.bend_stiffness);
  require(f, p.bend_stiffness >= 0, "bend_stiffness", "must be >= 0 (N m^2)");
  f.get("root_stiffness", p.root_stiffness);
  require(f, p.root_stiffness >= 0, "root_stiffness", "must be >= 0");
  f.get("damping", p.damping);
  require(f, p.damping >= 0, "damping", "must be >= 0 (1/s)");
  f.get("air_drag", p.air_drag);
  require(f, p.air_drag >= 0, "air_drag", "must be >= 0 (1/s)");
  f.get("collision", p.collision);
  f.get("collision_margin", p.collision_margin);
  require(f, p.collision_margin >= 0, "collision_margin", "must be >= 0 (m)");
  f.get("max_speed", p.max_speed);
  require(f, p.max_speed > 0, "max_speed", "must be positive (m/s)");
  f.get("preroll", p.preroll);
  require(f, p.preroll >= 0 && p.preroll <= 600, "preroll", "must be in [0, 600] seconds");
  if (const json* wind = f.find("wind")) {
    Fields w(*wind, "sim.wind", f.file());
    w.get("velocity", p.wind.velocity);
    w.get("gust", p.wind.gust);
    require(w, p.wind.gust >= 0, "gust", "must be >= 0 (m/s)");
    w.get("gust_frequency", p.wind.gust_frequency);
    require(w, p.wind.gust_frequency >= 0, "gust_frequency", "must be >= 0 (Hz)");
    w.get("seed", p.wind.seed);
    w.finish();
  }
}

void parse_camera(Fields& f, Scene& s) {
  sim::CameraParams& c = s.camera;
  f.get("eye", c.eye);
  f.get("target", c.target);
  f.get("up", c.up);
  require(f, (c.target - c.eye).norm() > 1e-9, "target", "must differ from camera.eye");
  require(f, (c.target - c.eye).cross(c.up).norm() > 1e-9, "up",
          "must not be parallel to the view");
  f.get("fov_deg", c.fov_deg);
  require(f, c.fov_deg > 0 && c.fov_deg < 180, "fov_deg", "must be in (0, 180)");
  f.get("width", c.width);
  require(f, c.width >= 1 && c.width <= 65536, "width", "must be in [1, 65536] pixels");
  f.get("height", c.height);
  require(f, c.height >= 1 && c.height <= 65536, "height", "must be in [1, 65536] pixels");
  f.get("hysteresis", c.hysteresis);
  require(f, c.hysteresis >= 0, "hysteresis", "must be >= 0 (m)");
}

// Relative file names inside a style resolve from the folder of the file that names them.
std::filesystem::path folder_of(const Fields& f) {
  return std::filesystem::path(f.file()).parent_path();
}

void parse_shading(Fields& f, vector::HairStyle& st) {
  vector::ShadingStyle& s = st.shading;
  std::string model = s.model == vector::ShadingModel::Lit ? "lit" : "faraj";
  f.choice("model", model, {"faraj", "lit"});
  s.model = model == "lit" ? vector::ShadingModel::Lit : vector::ShadingModel::Faraj;
  if (const json* r = f.find("ramp")) {
    if (r->is_null()) {
      s.ramp.reset();
    } else {
      if (!r->is_string() || r->get<std::string>().empty())
        f.fail(f.name("ramp"), "expected an image file name or null, got " + r->dump());
      const std::string file = r->get<std::string>();
      const std::filesystem::path p = std::filesystem::path(file).is_absolute()
                                          ? std::filesystem::path(file)
                                          : folder_of(f) / file;
      try {
        s.ramp = read_ramp(p);
      } catch (const std::exception& e) {
        f.fail(f.name("ramp"), e.what());
      }
    }
  }
  static const std::vector<std::pair<std::string, vector::RampMetric>> metrics = {
      {"none", vector::RampMetric::None},
      {"depth", vector::RampMetric::Depth},
      {"back_light", vector::RampMetric::BackLight},
      {"specular", vector::RampMetric::Specular}};
  std::string metric;
  for (const auto& [name, m] : metrics)
    if (m == s.metric) metric = name;
  f.choice("ramp_metric", metric, {"none", "depth", "back_light", "specular"});
  for (const auto& [name, m] : metrics)
    if (name == metric) s.metric = m;
  f.color("ramp_tint", s.ramp_tint);
  f.get("hard_bands", s.hard_bands);
  f.get("band_threshold", s.band_threshold);
  require(f, s.band_threshold > 0 && s.band_threshold <= 1, "band_threshold",
          "must be in (0, 1] (a colour difference)");
  vector::Lighting& l = s.lighting;
  for (auto [key, v] : {std::pair<const char*, double*>{"ambient", &l.ambient},
                        {"kajiya_diffuse", &l.kajiya_diffuse},
                        {"lambert", &l.lambert},
                        {"specular", &l.specular}}) {
    f.get(key, *v);
    require(f, *v >= 0 && *v <= 10, key, "must be a weight in [0, 10]");
  }
  f.get("shininess", l.shininess);
  require(f, l.shininess > 0 && l.shininess <= 10000, "shininess", "must be in (0, 10000]");
  f.get("head_shadow", l.head_shadow);
  require(f, l.head_shadow >= 0 && l.head_shadow <= 1, "head_shadow", "must be in [0, 1]");
  f.get("head_offset", l.head_offset);
  require(f, l.head_offset >= -1 && l.head_offset <= 1, "head_offset", "must be in [-1, 1]");
  f.get("back_exponent", l.back_exponent);
  require(f, l.back_exponent >= 0 && l.back_exponent <= 100, "back_exponent",
          "must be in [0, 100]");
  f.get("depth_near", s.depth_near);
  require(f, s.depth_near >= 0, "depth_near", "must be >= 0 metres (0: the frame's nearest hair)");
  f.get("depth_far", s.depth_far);
  require(f, s.depth_far >= 0, "depth_far", "must be >= 0 metres (0: the frame's farthest hair)");
  require(f, s.depth_near == 0 || s.depth_far == 0 || s.depth_far > s.depth_near, "depth_far",
          "must be greater than depth_near");
  f.get("metric_shininess", s.metric_shininess);
  require(f, s.metric_shininess > 0 && s.metric_shininess <= 10000, "metric_shininess",
          "must be in (0, 10000]");
  f.get("centre_line", s.centre_line);
  f.get("sample_px", s.sample_px);
  require(f, s.sample_px >= 0.25 && s.sample_px <= 100, "sample_px",
          "must be in [0.25, 100] pixels");
}

void parse_highlights(Fields& f, vector::HairStyle& st) {
  vector::HighlightStyle& h = st.specular;
  static const std::vector<std::pair<std::string, vector::HighlightShape>> shapes = {
      {"none", vector::HighlightShape::None},
      {"band", vector::HighlightShape::Band},
      {"anime", vector::HighlightShape::Anime}};
  std::string shape;
  for (const auto& [name, v] : shapes)
    if (v == h.shape) shape = name;
  f.choice("shape", shape, {"none", "band", "anime"});
  for (const auto& [name, v] : shapes)
    if (name == shape) h.shape = v;
  f.color("color", h.color);
  f.get("threshold", h.threshold);
  require(f, h.threshold > 0 && h.threshold < 1, "threshold", "must be in (0, 1)");
  f.get("shininess", h.shininess);
  require(f, h.shininess > 0 && h.shininess <= 10000, "shininess", "must be in (0, 10000]");
  f.get("max_width", h.max_width);
  require(f, h.max_width > 0 && h.max_width <= 1, "max_width",
          "must be in (0, 1] (a fraction of the wisp's half-width)");
  f.get("teeth", h.teeth);
  require(f, h.teeth >= 1 && h.teeth <= 16, "teeth", "must be in [1, 16]");
  f.get("band_width_deg", h.band_width_deg);
  require(f, h.band_width_deg > 0 && h.band_width_deg <= 90, "band_width_deg",
          "must be in (0, 90] degrees");
  f.get("band_extent_deg", h.band_extent_deg);
  require(f, h.band_extent_deg >= 1 && h.band_extent_deg <= 180, "band_extent_deg",
          "must be in [1, 180] degrees");
  f.get("band_shift_deg", h.band_shift_deg);
  require(f, h.band_shift_deg >= -90 && h.band_shift_deg <= 90, "band_shift_deg",
          "must be in [-90, 90] degrees");
  f.get("tooth_depth", h.tooth_depth);
  require(f, h.tooth_depth >= 0 && h.tooth_depth <= 10, "tooth_depth",
          "must be in [0, 10] band widths");
}

void parse_ink(Fields& f, vector::HairStyle& st) {
  vector::InkStyle& k = st.ink;
  f.get("silhouette_width", k.silhouette_width);
  require(f, k.silhouette_width >= 0 && k.silhouette_width <= 1000, "silhouette_width",
          "must be a width in [0, 1000] pixels (0: no silhouette ink)");
  f.get("occlusion_width", k.occlusion_width);
  require(f, k.occlusion_width >= 0 && k.occlusion_width <= 1000, "occlusion_width",
          "must be a width in [0, 1000] pixels (0: no occlusion ink)");
  f.get("reference_size", k.reference_size);
  require(f, k.reference_size >= 1 && k.reference_size <= 65536, "reference_size",
          "must be in [1, 65536] pixels");
  f.color("color", k.color);
  f.get("root_fade", k.root_fade);
  require(f, k.root_fade >= 0 && k.root_fade <= 1, "root_fade",
          "must be in [0, 1] (a fraction of the strand; 0: no taper)");
  f.get("root_width", k.root_width);
  require(f, k.root_width >= 0 && k.root_width <= 1, "root_width",
          "must be in [0, 1] (the width factor at the root)");
  f.get("tip_fade", k.tip_fade);
  require(f, k.tip_fade >= 0 && k.tip_fade <= 1, "tip_fade",
          "must be in [0, 1] (a fraction of the strand; 0: no taper)");
  f.get("tip_width", k.tip_width);
  require(f, k.tip_width >= 0 && k.tip_width <= 1, "tip_width",
          "must be in [0, 1] (the width factor at the tip)");
  f.get("end_taper", k.end_taper);
  require(f, k.end_taper >= 0, "end_taper", "must be >= 0 pixels");
  f.get("fit_tolerance", k.fit_tolerance);
  require(f, k.fit_tolerance > 0 && k.fit_tolerance <= 5, "fit_tolerance",
          "must be in (0, 5] pixels");
}

void parse_base(Fields& f, vector::HairStyle& st) {
  vector::BaseStyle& b = st.base;
  f.get("enabled", b.enabled);
  f.get("tone", b.tone);
  require(f, b.tone >= 0 && b.tone <= 1, "tone",
          "must be in [0, 1] (0: the shadow colour, 1: the hair colour)");
  f.get("spread", b.spread);
  require(f, b.spread >= 0.25 && b.spread <= 8, "spread", "must be in [0.25, 8] root spacings");
  f.get("level", b.level);
  require(f, b.level > 0 && b.level < 1, "level", "must be in (0, 1) (a coverage level)");
}

// A nested object of the style, parsed by `parse` and checked for unknown keys.
template <void (*parse)(Fields&, vector::HairStyle&)>
void style_object(Fields& f, const char* k, vector::HairStyle& s) {
  const json* v = f.find(k);
  if (!v) return;
  Fields g(*v, f.name(k), f.file());
  parse(g, s);
  g.finish();
}

// The `style` part, one entry per JSON field: presets and lighting fields join this table.
using StyleField = std::function<void(Fields&, const char* key, vector::HairStyle&)>;

const std::vector<std::pair<const char*, StyleField>>& style_fields() {
  using vector::HairStyle;
  static const std::vector<std::pair<const char*, StyleField>> table = {
      {"width",
       [](Fields& f, const char* k, HairStyle& s) {
         f.get(k, s.geometry.width);
         require(f, s.geometry.width > 0 && s.geometry.width <= 1, k,
                 "must be a width in (0, 1] metres");
       }},
      {"profile",
       [](Fields& f, const char* k, HairStyle& s) {
         if (!f.find(k)) return;
         std::string name = "taper";
         f.choice(k, name, {"taper", "sine"});
         s.geometry.profile =
             name == "sine" ? vector::WidthProfile::shin() : vector::WidthProfile::faraj_taper();
       }},
      {"root_taper",
       [](Fields& f, const char* k, HairStyle& s) {
         f.get(k, s.geometry.root_taper);
         require(f, s.geometry.root_taper >= 0 && s.geometry.root_taper <= 1, k,
                 "must be in [0, 1] (a fraction of the strand; 0: no taper)");
       }},
      {"curvature_clamp",
       [](Fields& f, const char* k, HairStyle& s) {
         const json* v = f.find(k);
         if (!v) return;
         if (v->is_null()) {
           s.geometry.curvature_clamp = std::numeric_limits<double>::infinity();
           return;
         }
         s.geometry.curvature_clamp = f.number(*v, f.name(k));
         require(f, s.geometry.curvature_clamp > 0, k, "must be > 0 (null disables the clamp)");
       }},
      {"hair_color", [](Fields& f, const char* k, HairStyle& s) { f.color(k, s.hair); }},
      {"shadow_color", [](Fields& f, const char* k, HairStyle& s) { f.color(k, s.shadow); }},
      {"highlight_color", [](Fields& f, const char* k, HairStyle& s) { f.color(k, s.highlight); }},
      {"highlight_along",
       [](Fields& f, const char* k, HairStyle& s) {
         f.get(k, s.highlight_along);
         require(f, s.highlight_along >= 0 && s.highlight_along <= 1, k, "must be in [0, 1]");
       }},
      {"highlight_spread",
       [](Fields& f, const char* k, HairStyle& s) {
         f.get(k, s.highlight_spread);
         require(f, s.highlight_spread > 0 && s.highlight_spread <= 1, k, "must be in (0, 1]");
       }},
      {"highlight_side",
       [](Fields& f, const char* k, HairStyle& s) {
         std::string side = s.highlight_on_left ? "left" : "right";
         f.choice(k, side, {"left", "right"});
         s.highlight_on_left = side == "left";
       }},
      {"shading", style_object<parse_shading>},
      {"highlights", style_object<parse_highlights>},
      {"ink", style_object<parse_ink>},
      {"base", style_object<parse_base>},
  };
  return table;
}

// Cross-field checks of a whole style; `f` names the object in messages.
void check_style(Fields& f, const vector::HairStyle& st) {
  try {
    vector::validate(st.geometry);
  } catch (const std::invalid_argument& e) {
    f.fail("style", e.what());
  }
  const vector::Lighting& l = st.shading.lighting;
  if (st.shading.model == vector::ShadingModel::Lit &&
      !(l.ambient + l.kajiya_diffuse + l.lambert > 0))
    f.fail(f.name("shading"),
           "lit shading needs a positive ambient, kajiya_diffuse or lambert weight");
}

// The folder of data/ (presets and ramps): $WISP_DATA_DIR, or the source tree's data/ folder
// (WISP_SOURCE_DATA_DIR, set by io/CMakeLists.txt).
std::filesystem::path data_dir() {
  if (const char* env = std::getenv("WISP_DATA_DIR"); env && *env) return env;
  return WISP_SOURCE_DATA_DIR;
}

// Names of the presets in data/styles.
std::vector<std::string> preset_names() {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(data_dir() / "styles", ec))
    if (e.path().extension() == ".json") names.push_back(e.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

// Reads a preset (a name in data/styles, or a .json file relative to the scene) into the style:
// a JSON object with the style's fields (except `preset`) and an optional `description`.
void apply_preset(Fields& f, const std::string& value, Scene& s) {
  const std::string field = f.name("preset");
  std::filesystem::path path;
  if (value.size() > 5 && value.substr(value.size() - 5) == ".json") {
    path = resolve(s.path, value);
  } else {
    const std::vector<std::string> names = preset_names();
    if (std::find(names.begin(), names.end(), value) == names.end()) {
      std::string list;
      for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
      f.fail(field, "expected one of " +
                        (list.empty() ? "(no presets found in " + (data_dir() / "styles").string() +
                                            "; set WISP_DATA_DIR)"
                                      : list) +
                        " or a .json file, got \"" + value + "\"" + Fields::suggest(value, names));
    }
    path = data_dir() / "styles" / (value + ".json");
  }
  std::ifstream in(path);
  if (!in) f.fail(field, path.string() + ": cannot open the preset file");
  json doc;
  try {
    doc = json::parse(in);
  } catch (const json::exception& e) {
    f.fail(field, path.string() + ": invalid JSON: " + e.what());
  }
  try {
    Fields p(doc, "", path.string());
    if (const json* d = p.find("description"))
      if (!d->is_string()) p.fail("description", "expected a string");
    for (const auto& [key, read] : style_fields()) read(p, key, s.style);
    p.finish();
  } catch (const std::invalid_argument& e) {
    f.fail(field, e.what());
  }
}

void parse_style(Fields& f, Scene& s) {
  // A preset first, whatever the order of the keys: the scene's own fields override it.
  if (const json* p = f.find("preset")) {
    if (!p->is_string())
      f.fail(f.name("preset"), "expected a preset name or a .json file, got " + p->dump());
    apply_preset(f, p->get<std::string>(), s);
  }
  for (const auto& [key, read] : style_fields()) read(f, key, s.style);
  check_style(f, s.style);
}

void parse_light(Fields& f, Scene& s) {
  f.get("direction", s.light_dir);
  require(f, s.light_dir.norm() > 1e-9, "direction", "must be a non-zero vector");
  s.light_dir.normalize();
}

void parse_render(Fields& f, Scene& s) {
  RenderParams& r = s.render;
  f.color("background_color", r.background_color);
  f.color("skin_color", r.skin_color);
  f.get("body", r.body);
  f.get("torso", r.torso);
  f.get("solver_tolerance", r.solver_tolerance);
  require(f, r.solver_tolerance > 0 && r.solver_tolerance < 1, "solver_tolerance",
          "must be in (0, 1) (relative residual)");
  f.get("warm_start_block", r.warm_start_block);
  require(f, r.warm_start_block >= 1 && r.warm_start_block <= 100000, "warm_start_block",
          "must be in [1, 100000] frames");
  f.get("video", r.video);
  f.get("contact_sheet_columns", r.contact_sheet_columns);
  require(f, r.contact_sheet_columns >= 1 && r.contact_sheet_columns <= 100,
          "contact_sheet_columns", "must be in [1, 100]");
}

// The parts of a scene.
const std::map<std::string, std::function<void(Fields&, Scene&)>>& parts() {
  static const std::map<std::string, std::function<void(Fields&, Scene&)>> table = {
      {"head", parse_head},   {"hair", parse_hair},     {"motion", parse_motion},
      {"sim", parse_sim},     {"camera", parse_camera}, {"style", parse_style},
      {"light", parse_light}, {"render", parse_render},
  };
  return table;
}

}  // namespace

Scene parse_scene(const json& doc, const std::filesystem::path& path) {
  Scene scene;
  scene.path = path;
  Fields top(doc, "", path.string());
  for (const auto& [name, parse] : parts())
    if (const json* part = top.find(name.c_str())) {
      Fields f(*part, name, path.string());
      parse(f, scene);
      f.finish();
    }
  top.finish();
  return scene;
}

Scene load_scene(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path.string() + ": cannot open the scene file");
  json doc;
  try {
    doc = json::parse(in);
  } catch (const json::exception& e) {
    // nlohmann's message carries the line and column (or the overflowing number).
    std::string what = e.what();
    auto at = what.find("] ");
    at = at == std::string::npos ? at : at + 2;
    throw std::invalid_argument(
        path.string() + ": invalid JSON: " + (at == std::string::npos ? what : what.substr(at)));
  }
  return parse_scene(doc, path);
}

}  // namespace wisp::io
