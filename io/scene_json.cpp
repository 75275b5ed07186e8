// Scene JSON reader: see scene.hpp. Each part is a small function over a field reader that
// remembers which keys it consumed, so whatever is left over is an unknown field, reported with
// the nearest known name when it looks like a typo. Choices are read by their names
// (sim/choices.hpp); ranges are left to each struct's own validate(), called once per part.
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

#include "io/input_file.hpp"
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
      if (!v->is_number_integer()) fail(name(key), "expected an integer, got " + json_excerpt(*v));
      const auto n = v->get<long long>();
      if (n < -1000000000LL || n > 1000000000LL) fail(name(key), "out of range");
      out = static_cast<int>(n);
    }
  }
  void get(const char* key, std::uint64_t& out) {
    if (const json* v = find(key)) {
      if (!v->is_number_unsigned())
        fail(name(key), "expected a non-negative integer, got " + json_excerpt(*v));
      out = v->get<std::uint64_t>();
    }
  }
  void get(const char* key, bool& out) {
    if (const json* v = find(key)) {
      if (!v->is_boolean()) fail(name(key), "expected true or false, got " + json_excerpt(*v));
      out = v->get<bool>();
    }
  }
  void get(const char* key, std::string& out) {
    if (const json* v = find(key)) {
      if (!v->is_string()) fail(name(key), "expected a string, got " + json_excerpt(*v));
      out = v->get<std::string>();
    }
  }
  // A list of numbers.
  void get(const char* key, std::vector<double>& out) {
    if (const json* v = find(key)) {
      if (!v->is_array()) fail(name(key), "expected an array of numbers, got " + json_excerpt(*v));
      out.clear();
      for (std::size_t i = 0; i < v->size(); ++i)
        out.push_back(number((*v)[i], name(key) + "[" + std::to_string(i) + "]"));
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
        fail(name(key), "colour components must be in [0, 1], got " + json_excerpt(*v));
      out = c.cast<float>();
    }
  }
  // One of the names in `table` (sim/choices.hpp).
  template <class Table, class T>
  void choice(const char* key, T& out, const Table& table) {
    if (!find(key)) return;
    std::string given;
    get(key, given);
    if (const auto value = sim::parse_choice(table, given)) {
      out = *value;
      return;
    }
    const std::vector<std::string> names = sim::choice_names(table);
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    fail(name(key), "expected one of " + list + ", got \"" + given + "\"" + suggest(given, names));
  }
  // One of the names of the enum E (its choices(E) table).
  template <class E>
  void choice(const char* key, E& out) {
    choice(key, out, choices(E{}));
  }

  double number(const json& v, const std::string& field) const {
    if (!v.is_number()) fail(field, "expected a number, got " + json_excerpt(v));
    const double d = v.get<double>();
    if (!std::isfinite(d)) fail(field, "not a finite number");
    return d;
  }
  Eigen::Vector3d vector3(const json& v, const std::string& field) const {
    if (!v.is_array() || v.size() != 3)
      fail(field, "expected an array of 3 numbers, got " + json_excerpt(v));
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

  // The validate() of the struct this object filled (sim/params.hpp): its "field: what" gets
  // the file and this object's path in front ("scene.json: hair.count: ...").
  template <class Params>
  void check(const Params& params) const {
    try {
      if (where_.empty())
        validate(params);
      else
        sim::validate_part(params, where_);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(file_ + ": " + e.what());
    }
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

std::filesystem::path resolve(const std::filesystem::path& scene, const std::string& file) {
  const std::filesystem::path p(file);
  return p.is_absolute() ? p : scene.parent_path() / p;
}

void parse_head(Fields& f, Scene& s) {
  sim::HeadParams& h = s.head;
  f.choice("shape", h.shape);
  f.get("radii", h.radii);
  std::string mesh;
  f.get("mesh", mesh);
  if (!mesh.empty()) h.mesh = resolve(s.path, mesh);
  f.get("mesh_scale", h.mesh_scale);
  f.get("mesh_offset", h.mesh_offset);
  f.get("shoulders", h.shoulders);
  f.get("shoulder_center", h.shoulder_center);
  f.get("shoulder_half_width", h.shoulder_half_width);
  f.get("shoulder_radius", h.shoulder_radius);
  f.get("torso_turn", h.torso_turn);
  f.check(h);
}

void parse_hair(Fields& f, Scene& s) {
  sim::HairParams& h = s.hair;
  f.choice("source", h.source);
  std::string file;
  f.get("file", file);
  if (!file.empty()) h.file = resolve(s.path, file);
  f.get("count", h.count);
  f.get("guides", h.guides);
  f.get("segments", h.segments);
  f.get("length", h.length);
  f.get("length_variation", h.length_variation);
  f.choice("style", h.style);
  f.get("amplitude", h.amplitude);
  f.get("frequency", h.frequency);
  f.get("parting_deg", h.parting_deg);
  f.get("comb", h.comb);
  f.get("scalp_angle_deg", h.scalp_angle_deg);
  f.get("face_angle_deg", h.face_angle_deg);
  f.get("seed", h.seed);
  f.get("file_scale", h.file_scale);
  f.get("file_offset", h.file_offset);
  f.get("file_z_up", h.file_z_up);
  f.check(h);
}

void parse_fur(Fields& f, Scene& s) {
  sim::FurParams& u = s.fur;
  f.get("count", u.count);
  f.get("length", u.length);
  f.get("length_variation", u.length_variation);
  f.get("strands", u.strands);
  f.get("clump_radius", u.clump_radius);
  f.get("clump", u.clump);
  f.get("scalp_angle_deg", u.scalp_angle_deg);
  f.get("face_angle_deg", u.face_angle_deg);
  f.get("comb_direction", u.comb_direction);
  f.get("comb", u.comb);
  f.get("stiffness", u.stiffness);
  f.get("damping", u.damping);
  f.get("drag", u.drag);
  f.get("step_rate", u.step_rate);
  f.get("seed", u.seed);
  f.check(u);
}

void parse_motion(Fields& f, Scene& s) {
  sim::MotionParams& m = s.motion;
  f.choice("preset", m.preset);
  f.get("duration", m.duration);
  f.get("amplitude", m.amplitude);
  f.get("speed", m.speed);
  f.get("settle", m.settle);
  if (const json* keys = f.find("keys")) {
    if (!keys->is_array()) f.fail("motion.keys", "expected an array of keyframes");
    for (std::size_t i = 0; i < keys->size(); ++i) {
      Fields k((*keys)[i], "motion.keys[" + std::to_string(i) + "]", f.file());
      sim::Keyframe key;
      k.get("time", key.time);
      k.get("position", key.position);
      k.get("ypr_deg", key.ypr_deg);
      k.finish();
      m.keys.push_back(key);
    }
  }
  f.check(m);
}

void parse_sim(Fields& f, Scene& s) {
  sim::SimParams& p = s.sim;
  f.choice("model", p.model);
  f.get("fps", p.fps);
  f.get("step_rate", p.step_rate);
  f.get("substeps", p.substeps);
  f.get("iterations", p.iterations);
  f.get("gravity", p.gravity);
  f.get("density", p.density);
  f.get("bend_stiffness", p.bend_stiffness);
  f.get("root_stiffness", p.root_stiffness);
  f.get("damping", p.damping);
  f.get("air_drag", p.air_drag);
  f.get("collision", p.collision);
  f.get("collision_margin", p.collision_margin);
  f.get("max_speed", p.max_speed);
  f.get("preroll", p.preroll);
  if (const json* wind = f.find("wind")) {
    Fields w(*wind, "sim.wind", f.file());
    w.get("velocity", p.wind.velocity);
    w.get("gust", p.wind.gust);
    w.get("gust_frequency", p.wind.gust_frequency);
    w.get("seed", p.wind.seed);
    w.finish();
  }
  f.check(p);
}

void parse_camera(Fields& f, Scene& s) {
  sim::CameraParams& c = s.camera;
  f.get("eye", c.eye);
  f.get("target", c.target);
  f.get("up", c.up);
  f.get("fov_deg", c.fov_deg);
  f.get("width", c.width);
  f.get("height", c.height);
  f.get("hysteresis", c.hysteresis);
  f.get("focus_distance", c.focus_distance);
  f.get("aperture", c.aperture);
  f.check(c);
}

// Relative file names inside a style resolve from the folder of the file that names them.
std::filesystem::path folder_of(const Fields& f) {
  return std::filesystem::path(f.file()).parent_path();
}

void parse_shading(Fields& f, vector::HairStyle& st) {
  vector::ShadingStyle& s = st.shading;
  f.choice("model", s.model);
  if (const json* r = f.find("ramp")) {
    if (r->is_null()) {
      s.ramp.reset();
    } else {
      if (!r->is_string() || r->get<std::string>().empty())
        f.fail(f.name("ramp"), "expected an image file name or null, got " + json_excerpt(*r));
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
  f.choice("ramp_metric", s.metric);
  f.color("ramp_tint", s.ramp_tint);
  f.get("hard_bands", s.hard_bands);
  f.get("band_threshold", s.band_threshold);
  vector::Lighting& l = s.lighting;
  f.get("ambient", l.ambient);
  f.get("kajiya_diffuse", l.kajiya_diffuse);
  f.get("lambert", l.lambert);
  f.get("specular", l.specular);
  f.get("shininess", l.shininess);
  f.get("head_shadow", l.head_shadow);
  f.get("head_offset", l.head_offset);
  f.get("back_exponent", l.back_exponent);
  f.get("depth_near", s.depth_near);
  f.get("depth_far", s.depth_far);
  f.get("metric_shininess", s.metric_shininess);
  f.get("centre_line", s.centre_line);
  f.get("sample_px", s.sample_px);
}

void parse_highlights(Fields& f, vector::HairStyle& st) {
  vector::HighlightStyle& h = st.specular;
  f.choice("shape", h.shape);
  f.color("color", h.color);
  f.get("threshold", h.threshold);
  f.get("shininess", h.shininess);
  f.get("max_width", h.max_width);
  f.get("teeth", h.teeth);
  f.get("band_width_deg", h.band_width_deg);
  f.get("band_extent_deg", h.band_extent_deg);
  f.get("band_shift_deg", h.band_shift_deg);
  f.get("tooth_depth", h.tooth_depth);
}

void parse_ink(Fields& f, vector::HairStyle& st) {
  vector::InkStyle& k = st.ink;
  f.get("silhouette_width", k.silhouette_width);
  f.get("occlusion_width", k.occlusion_width);
  f.get("reference_size", k.reference_size);
  f.color("color", k.color);
  f.get("root_fade", k.root_fade);
  f.get("root_width", k.root_width);
  f.get("tip_fade", k.tip_fade);
  f.get("tip_width", k.tip_width);
  f.get("end_taper", k.end_taper);
  f.get("fit_tolerance", k.fit_tolerance);
}

void parse_blur(Fields& f, vector::HairStyle& st) {
  vector::BlurStyle& b = st.blur;
  f.get("tip", b.tip);
  f.get("tip_fade", b.tip_fade);
  f.get("shutter", b.shutter);
  f.get("max", b.max);
  f.get("reference_size", b.reference_size);
}

void parse_fur_style(Fields& f, vector::HairStyle& st) {
  vector::FurStyle& u = st.fur;
  f.get("strand_width", u.strand_width);
  f.get("fin_band", u.fin_band);
  f.get("interior_opacity", u.interior_opacity);
  f.get("max_opacity", u.max_opacity);
  f.get("min_width_px", u.min_width_px);
}

void parse_base(Fields& f, vector::HairStyle& st) {
  vector::BaseStyle& b = st.base;
  f.get("enabled", b.enabled);
  f.get("tone", b.tone);
  f.get("spread", b.spread);
  f.get("level", b.level);
}

void parse_hatching(Fields& f, vector::HairStyle& st) {
  vector::HatchStyle& h = st.hatching;
  f.get("enabled", h.enabled);
  f.get("tones", h.tones);
  f.get("coverage", h.coverage);
  f.get("cross", h.cross);
  f.get("cross_angle_deg", h.cross_angle_deg);
  f.get("width", h.width);
  f.get("length", h.length);
  f.get("length_jitter", h.length_jitter);
  f.get("lanes", h.lanes);
  f.get("reach", h.reach);
  f.get("candidates", h.candidates);
  f.get("soft", h.soft);
  f.get("end_taper", h.end_taper);
  f.color("color", h.color);
  f.get("seed", h.seed);
  f.get("body", h.body);
  f.get("body_tones", h.body_tones);
  f.get("body_spacing", h.body_spacing);
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
      {"width", [](Fields& f, const char* k, HairStyle& s) { f.get(k, s.geometry.width); }},
      {"profile",
       [](Fields& f, const char* k, HairStyle& s) {
         if (!f.find(k)) return;
         auto shape = vector::WidthProfile::Shape::Linear;
         f.choice(k, shape);
         s.geometry.profile = shape == vector::WidthProfile::Shape::Shin
                                  ? vector::WidthProfile::shin()
                                  : vector::WidthProfile::faraj_taper();
       }},
      {"root_taper",
       [](Fields& f, const char* k, HairStyle& s) { f.get(k, s.geometry.root_taper); }},
      {"curvature_clamp",
       [](Fields& f, const char* k, HairStyle& s) {
         const json* v = f.find(k);
         if (!v) return;
         if (v->is_null()) {
           s.geometry.curvature_clamp = std::numeric_limits<double>::infinity();
           return;
         }
         s.geometry.curvature_clamp = f.number(*v, f.name(k));
       }},
      {"flatten_tolerance",
       [](Fields& f, const char* k, HairStyle& s) { f.get(k, s.geometry.flatten_tolerance_px); }},
      {"hair_color", [](Fields& f, const char* k, HairStyle& s) { f.color(k, s.hair); }},
      {"shadow_color", [](Fields& f, const char* k, HairStyle& s) { f.color(k, s.shadow); }},
      {"highlight_color", [](Fields& f, const char* k, HairStyle& s) { f.color(k, s.highlight); }},
      {"highlight_along",
       [](Fields& f, const char* k, HairStyle& s) { f.get(k, s.highlight_along); }},
      {"highlight_spread",
       [](Fields& f, const char* k, HairStyle& s) { f.get(k, s.highlight_spread); }},
      {"highlight_side",
       [](Fields& f, const char* k, HairStyle& s) {
         static constexpr std::array<sim::Choice<bool>, 2> on_left{
             {{"left", true}, {"right", false}}};
         f.choice(k, s.highlight_on_left, on_left);
       }},
      {"shading", style_object<parse_shading>},
      {"highlights", style_object<parse_highlights>},
      {"ink", style_object<parse_ink>},
      {"base", style_object<parse_base>},
      {"blur", style_object<parse_blur>},
      {"hatching", style_object<parse_hatching>},
      {"fur", style_object<parse_fur_style>},
  };
  return table;
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
  json doc;
  try {
    doc = parse_json(read_input_file(path, "style preset file"), path.string());
  } catch (const std::exception& e) {
    f.fail(field, e.what());
  }
  try {
    Fields p(doc, "", path.string());
    if (const json* d = p.find("description"))
      if (!d->is_string()) p.fail("description", "expected a string");
    for (const auto& [key, read] : style_fields()) read(p, key, s.style);
    p.finish();
    p.check(s.style);
  } catch (const std::invalid_argument& e) {
    f.fail(field, e.what());
  }
}

void parse_style(Fields& f, Scene& s) {
  // A preset first, whatever the order of the keys: the scene's own fields override it.
  if (const json* p = f.find("preset")) {
    if (!p->is_string())
      f.fail(f.name("preset"), "expected a preset name or a .json file, got " + json_excerpt(*p));
    apply_preset(f, p->get<std::string>(), s);
  }
  for (const auto& [key, read] : style_fields()) read(f, key, s.style);
  f.check(s.style);
}

void parse_light(Fields& f, Scene& s) {
  f.get("direction", s.light_dir);
  if (!(s.light_dir.norm() > 1e-9 && s.light_dir.cwiseAbs().maxCoeff() <= 1e6))
    f.fail(f.name("direction"), "must be a non-zero vector with components in [-1e6, 1e6]");
  s.light_dir.normalize();
}

void parse_render(Fields& f, Scene& s) {
  RenderParams& r = s.render;
  f.color("background_color", r.background_color);
  f.color("skin_color", r.skin_color);
  f.get("body", r.body);
  f.get("torso", r.torso);
  f.get("face", r.face);
  f.color("face_color", r.face_color);
  f.get("solver_tolerance", r.solver_tolerance);
  f.get("warm_start_block", r.warm_start_block);
  f.get("video", r.video);
  f.get("contact_sheet_columns", r.contact_sheet_columns);
  f.get("antialias", r.antialias);
  f.check(r);
}

// The parts of a scene.
const std::map<std::string, std::function<void(Fields&, Scene&)>>& parts() {
  static const std::map<std::string, std::function<void(Fields&, Scene&)>> table = {
      {"head", parse_head},     {"hair", parse_hair},   {"fur", parse_fur},
      {"motion", parse_motion}, {"sim", parse_sim},     {"camera", parse_camera},
      {"style", parse_style},   {"light", parse_light}, {"render", parse_render},
  };
  return table;
}

}  // namespace

void validate(const RenderParams& r) {
  if (!(r.solver_tolerance > 0 && r.solver_tolerance < 1))
    throw std::invalid_argument("solver_tolerance: must be in (0, 1) (relative residual)");
  if (r.warm_start_block < 1 || r.warm_start_block > 100000)
    throw std::invalid_argument("warm_start_block: must be in [1, 100000] frames");
  if (r.contact_sheet_columns < 1 || r.contact_sheet_columns > 100)
    throw std::invalid_argument("contact_sheet_columns: must be in [1, 100]");
}

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
  return parse_scene(parse_json(read_input_file(path, "scene file"), path.string()), path);
}

}  // namespace wisp::io
