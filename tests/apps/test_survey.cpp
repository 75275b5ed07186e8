// The robustness survey (docs/robustness.md): a table of bad inputs across every format and
// command, generated here from small valid files. Each case must be refused as README.md
// promises: exit code 2, exactly one line of output naming the file (or the option) at fault,
// no library internals in it, within 10 s, and the case's folder (inputs and outputs) exactly as
// it was: nothing written, nothing half-written, no empty output folder.
#include <catch2/catch.hpp>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "run_command.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

const std::string kWisp = WISP_BIN_DIR "/wisp";
const std::string kInspect = WISP_BIN_DIR "/wisp-inspect";

struct Case {
  std::string name;
  std::map<std::string, std::string> files;  // written into the case folder first
  std::string command;                       // "{d}" is the case folder
  std::string named;                         // the line must contain this
};

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size()))
    s.replace(at, from.size(), to);
  return s;
}

// Every entry of a folder tree with its size and modification time.
std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    const std::string key = e.path().lexically_relative(dir).string();
    out[key] = e.is_regular_file()
                   ? std::to_string(e.file_size()) + "@" +
                         std::to_string(e.last_write_time().time_since_epoch().count())
                   : "dir";
  }
  return out;
}

void run_case(const Case& c, int index) {
  const fs::path dir = wisp::test::fresh_folder("survey_" + std::to_string(index));
  for (const auto& [name, bytes] : c.files) {
    fs::create_directories((dir / name).parent_path());
    std::ofstream(dir / name, std::ios::binary) << bytes;
  }
  const auto before = snapshot(dir);
  const auto start = std::chrono::steady_clock::now();
  const wisp::test::CommandResult r =
      wisp::test::run_command("timeout 20 " + replace_all(c.command, "{d}", dir.string()));
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::string line = r.output;
  if (!line.empty() && line.back() == '\n') line.pop_back();
  INFO("case " << index << ": " << c.name << "\n  " << c.command << "\n  -> " << r.output);
  CHECK(r.exit_code == 2);
  CHECK(!line.empty());
  CHECK(line.find('\n') == std::string::npos);
  CHECK(line.find(replace_all(c.named, "{d}", dir.string())) != std::string::npos);
  for (const char* internal : {"basic_", "std::", "bad_alloc", "max_size", "cv::", "OpenCV",
                               "libpng", "Assertion", "terminate", "json.exception"})
    CHECK(line.find(internal) == std::string::npos);
  CHECK(seconds < 10);
  CHECK(snapshot(dir) == before);
  fs::remove_all(dir);
}

// Small valid inputs the cases break.
json tiny_scene() {
  return json::parse(R"({"hair": {"count": 3, "segments": 4}, "motion": {"duration": 0.1},
                         "sim": {"fps": 12}, "camera": {"width": 32, "height": 32}})");
}

std::string hair_file(std::uint32_t strands, std::uint32_t points, std::uint32_t flags,
                      std::size_t arrays_bytes) {
  std::string h = "HAIR";
  const auto put = [&](std::uint32_t v) { h.append(reinterpret_cast<const char*>(&v), 4); };
  put(strands), put(points), put(flags), put(points / std::max<std::uint32_t>(strands, 1) - 1);
  h.append(4 * 5, '\0');
  h.append(88, '\0');
  h.append(arrays_bytes, '\0');
  return h;
}

// A .hair file whose one strand of 3 points is given by its floats.
std::string hair_points(const std::vector<float>& xyz) {
  std::string h = hair_file(1, 3, 2, 0);
  h.append(reinterpret_cast<const char*>(xyz.data()), xyz.size() * 4);
  return h;
}

const char* kObj =
    "v 0.08 0 0\nv -0.08 0 0\nv 0 0.1 0\nv 0 -0.1 0\nv 0 0 0.09\nv 0 0 -0.09\n"
    "f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\nf 3 1 6\nf 2 3 6\nf 4 2 6\nf 1 4 6\n";

std::string png_bytes(int w, int h) {
  std::vector<unsigned char> out;
  cv::imencode(".png", cv::Mat(h, w, CV_8UC3, cv::Scalar(80, 120, 200)), out);
  return std::string(out.begin(), out.end());
}

std::uint32_t crc32(const std::string& s) {
  std::uint32_t c = 0xffffffffu;
  for (unsigned char b : s) {
    c ^= b;
    for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
  }
  return ~c;
}

// A PNG that announces w x h pixels but holds none.
std::string png_header_only(std::uint32_t w, std::uint32_t h) {
  const auto be = [](std::uint32_t v) {
    return std::string{char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
  };
  const std::string ihdr = "IHDR" + be(w) + be(h) + std::string{8, 2, 0, 0, 0};
  const std::string iend = "IEND";
  return std::string("\x89PNG\r\n\x1a\n", 8) + be(13) + ihdr + be(crc32(ihdr)) + be(0) + iend +
         be(crc32(iend));
}

std::string drawing(const std::string& point) {
  std::string xml = read(WISP_SOURCE_DIR "/data/drawings/circle.xml");
  return replace_all(xml, R"(x="406.000" y="256.000")", point);
}

// The .wsim of the tiny scene, with `edit` applied to its bytes (the checksum is recomputed).
std::string animation(const std::function<void(std::string&)>& edit = {}) {
  static const std::string bytes = [] {
    const fs::path dir = wisp::test::fresh_folder("survey_anim");
    std::ofstream(dir / "tiny.json") << tiny_scene().dump();
    const auto r = wisp::test::run_command(kWisp + " simulate " + (dir / "tiny.json").string() +
                                           " -o " + (dir / "tiny.wsim").string() + " -q");
    REQUIRE(r.exit_code == 0);
    return read(dir / "tiny.wsim");
  }();
  std::string b = bytes;
  if (!edit) return b;
  edit(b);
  b.resize(b.size() - 8);
  std::uint64_t h = 1469598103934665603ull;  // FNV-1a 64, as io/anim_file.cpp
  for (unsigned char c : b) h = (h ^ c) * 1099511628211ull;
  b.append(reinterpret_cast<const char*>(&h), 8);
  return b;
}

template <class T>
void poke(std::string& b, std::size_t at, T v) {
  std::memcpy(b.data() + at, &v, sizeof v);
}

std::vector<Case> scene_cases() {
  std::vector<Case> cases;
  const std::string simulate = kWisp + " simulate {d}/scene.json -o {d}/out.wsim -q";
  const auto add = [&](const std::string& name, const json& scene) {
    cases.push_back({name, {{"scene.json", scene.dump()}}, simulate, "scene.json"});
  };
  // One wrong value per field: wrong type, out of range, finite but huge.
  const std::vector<std::pair<std::string, std::vector<json>>> fields = {
      {"/head/radii", {json::array({0.1, 0, 0.1}), json::array({1e300, 0.1, 0.1}), "x"}},
      {"/head/mesh_scale", {0, 1e300, "x"}},
      {"/head/mesh_offset", {json::array({1e300, 0, 0}), json::array({0, 0})}},
      {"/head/shoulder_radius", {-1, 1e300}},
      {"/head/torso_turn", {2, "x"}},
      {"/hair/count", {-1, 1000000000, 1.5, "x"}},
      {"/fur/count", {-1, 1e9, 1.5}},
      {"/fur/length", {0, 1e12, "x"}},
      {"/fur/stiffness", {0, 1e300}},
      {"/fur/comb_direction", {json::array({1e300, 0, 0}), json::array({0, 0})}},
      {"/fur/clump", {-1, 2}},
      {"/hair/segments", {0, 5000, -3}},
      {"/hair/length", {0, 1e12, -1, "x"}},
      {"/hair/length_variation", {1, -0.5}},
      {"/hair/amplitude", {-1, 1e300}},
      {"/hair/frequency", {-1, 1e300}},
      {"/hair/parting_deg", {1e300}},
      {"/hair/comb", {-1, 1e300}},
      {"/hair/scalp_angle_deg", {0, 400}},
      {"/hair/face_angle_deg", {-1, 180}},
      {"/hair/seed", {-1, 1.5}},
      {"/hair/style", {"frizzy", 3}},
      {"/motion/duration", {0, 1e308, -1}},
      {"/motion/amplitude", {1e300}},
      {"/motion/speed", {0, 1e300}},
      {"/motion/settle", {-1, 1e300}},
      {"/motion/preset", {"dance"}},
      {"/sim/fps", {0, 1e308, -24}},
      {"/sim/step_rate", {1, 1e9}},
      {"/sim/substeps", {0, 100000}},
      {"/sim/iterations", {0, 100000}},
      {"/sim/gravity", {json::array({0, -1e300, 0})}},
      {"/sim/density", {0, 1e300}},
      {"/sim/bend_stiffness", {-1, 1e300}},
      {"/sim/damping", {1e300}},
      {"/sim/collision_margin", {1e300}},
      {"/sim/max_speed", {0}},
      {"/sim/preroll", {1e6}},
      {"/sim/model", {"verlet"}},
      {"/sim/wind/velocity", {json::array({1e300, 0, 0})}},
      {"/sim/wind/gust", {-1}},
      {"/camera/eye", {json::array({1e300, 0, 0}), json::array({0, -0.08, 0})}},
      {"/camera/target", {json::array({0, 1e300, 0})}},
      {"/camera/up", {json::array({0, 0, 0}), json::array({0, 1e300, 0})}},
      {"/camera/fov_deg", {0, 180}},
      {"/camera/width", {0, 65536, 100000}},
      {"/camera/height", {-1, 65536}},
      {"/camera/hysteresis", {1e300}},
      {"/light/direction", {json::array({0, 0, 0}), json::array({1e300, 1e300, 0})}},
      {"/render/solver_tolerance", {0, 2}},
      {"/render/warm_start_block", {0}},
      {"/render/contact_sheet_columns", {0, 1000}},
      {"/render/background_color", {json::array({2, 0, 0})}},
      {"/style/width", {-1, 1e300}},
      {"/style/preset", {"gothic", 3}},
      {"/style/hair_color", {json::array({0, 0})}},
      {"/hair/cuont", {3}},
  };
  for (const auto& [pointer, values] : fields)
    for (const json& v : values) {
      json scene = tiny_scene();
      scene[json::json_pointer(pointer)] = v;
      add(pointer + " = " + v.dump(), scene);
    }
  // Documented maxima multiplied together: refused by the budgets before any work.
  add("guides x segments", json::parse(R"({"hair": {"count": 100000, "segments": 1000}})"));
  add("step rate x substeps",
      json::parse(
          R"({"sim": {"step_rate": 100000, "substeps": 1000}, "motion": {"duration": 60}})"));
  add("long animation in memory",
      json::parse(R"({"hair": {"count": 10000, "segments": 50}, "sim": {"fps": 1000,
                     "step_rate": 1000}, "motion": {"duration": 10}})"));
  add("keys out of order", json::parse(R"({"motion": {"preset": "keys", "keys": [{"time": 1},
                                          {"time": 0}]}})"));
  add("key far away", json::parse(R"({"motion": {"preset": "keys", "keys": [{"time": 0,
                                     "position": [1e300, 0, 0]}]}})"));
  // Broken JSON.
  for (const std::string& text :
       {std::string("{"), std::string(""), std::string("[]"), std::string("{\"hair\": }"),
        std::string("{\"hair\": {\"count\": 1e999}}"), std::string("\xff\xfe{}"),
        std::string(40000, '[') + std::string(40000, ']'),
        "{\"hair\": " + std::string(50000, '[') + std::string(50000, ']') + "}",
        std::string("{\"style\": {\"hair_color\": ") + std::string(30000, '[') +
            std::string(30000, ']') + "}}",
        std::string("{\"a\\nb\": 1}")})
    cases.push_back({"JSON " + text.substr(0, 20), {{"scene.json", text}}, simulate, "scene.json"});
  // Paths that are not scene files.
  cases.push_back({"scene is a folder",
                   {{"scene/x", ""}},
                   kWisp + " simulate {d}/scene -o {d}/out.wsim -q",
                   "{d}/scene"});
  cases.push_back({"scene is missing", {}, simulate, "scene.json"});
  cases.push_back(
      {"scene is a device", {}, kWisp + " simulate /dev/null -o {d}/out.wsim -q", "/dev/null"});
  return cases;
}

std::vector<Case> file_cases() {
  std::vector<Case> cases;
  const std::string simulate = kWisp + " simulate {d}/scene.json -o {d}/out.wsim -q";
  const auto with = [&](const std::string& name, json hair_or_head, const std::string& file,
                        const std::string& bytes, const std::string& named) {
    json scene = tiny_scene();
    for (auto& [k, v] : hair_or_head.items()) scene[k].update(v);
    cases.push_back({name, {{"scene.json", scene.dump()}, {file, bytes}}, simulate, named});
  };
  const json hair = {{"hair", {{"source", "hair"}, {"file", "m.hair"}, {"count", 0}}}};
  with(".hair header of 4e9 strands", hair, "m.hair", hair_file(4000000000u, 3, 3, 0), "m.hair");
  with(".hair header of 4e9 points", hair, "m.hair", hair_file(1, 4000000000u, 2, 0), "m.hair");
  with(".hair truncated", hair, "m.hair", hair_file(1, 3, 2, 20), "m.hair");
  with(".hair trailing bytes", hair, "m.hair", hair_file(1, 3, 2, 40), "m.hair");
  with(".hair no points array", hair, "m.hair", hair_file(1, 3, 1, 2), "m.hair");
  with(".hair bad signature", hair, "m.hair", "HAIX" + hair_file(1, 3, 2, 36).substr(4), "m.hair");
  with(".hair short header", hair, "m.hair", "HAIR", "m.hair");
  with(".hair NaN point", hair, "m.hair", hair_points({0, 0, 0, NAN, 0, 0, 0, 1, 0}), "m.hair");
  with(".hair huge point", hair, "m.hair", hair_points({0, 0, 0, 3e38f, 0, 0, 0, 1, 0}),
       "hair.file_scale");
  with(".hair is a folder", hair, "m.hair/x", "", "m.hair");
  with(".hair missing", hair, "other", "", "m.hair");
  json scaled = hair;
  scaled["hair"]["file_scale"] = 1e6;
  with(".hair scaled far away", scaled, "m.hair", hair_points({0, 0, 0, 1, 0, 0, 2, 0, 0}),
       "hair.file_scale");

  const json strands = {{"hair", {{"source", "json"}, {"file", "s.json"}, {"count", 0}}}};
  for (const std::string& text :
       {std::string("{\"strands\": [[[0,0,0]]]}"), std::string("{\"strands\": 3}"),
        std::string("{\"strands\": [[[0,0,0],[0,1e308,0]]], \"x\": 1}"),
        std::string("{\"strands\": [[[0,0,0],[0,\"a\",0]]]}"), std::string("[1,2"),
        std::string("{\"format\": \"other\", \"strands\": []}"),
        std::string("{\"version\": 2, \"strands\": []}"),
        "{\"strands\": " + std::string(20000, '[') + std::string(20000, ']') + "}",
        std::string("{\"strands\": [[[0,0,0],[1e300,0,0]]]}"), std::string("{\"strands\": []}")})
    with("strand JSON " + text.substr(0, 30), strands, "s.json", text, "s.json");
  with("strand JSON folder", strands, "s.json/x", "", "s.json");

  const json mesh = {{"head", {{"shape", "mesh"}, {"mesh", "h.obj"}}}};
  for (const std::string& text :
       {std::string("v 1 2\n"), std::string("v 0 0 0\nf 1 2 3\n"),
        std::string("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n"), std::string("v nan 0 0\n"),
        std::string("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 x 3\n"), std::string("# nothing\n"),
        std::string("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n"),
        std::string("v 1e300 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\n"),
        std::string("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 1 2\n")})
    with("OBJ " + text.substr(0, 24), mesh, "h.obj", text,
         text.rfind("v 1e300", 0) == 0 ? "head.mesh_scale" : "h.obj");
  json big_mesh = mesh;
  big_mesh["head"]["mesh_scale"] = 1e6;
  with("OBJ scaled far away", big_mesh, "h.obj", kObj, "head.mesh_scale");
  with("OBJ is a folder", mesh, "h.obj/x", "", "h.obj");

  const json ramp = {{"style", {{"preset", "toon"}, {"shading", {{"ramp", "r.png"}}}}}};
  const std::string png = png_bytes(8, 2);
  with("ramp truncated", ramp, "r.png", png.substr(0, png.size() / 2), "r.png");
  with("ramp of 100000x100000", ramp, "r.png", png_header_only(100000, 100000), "r.png");
  with("ramp of 0 pixels", ramp, "r.png", png_header_only(0, 5), "r.png");
  with("ramp not an image", ramp, "r.png", "hello", "r.png");
  with("ramp empty", ramp, "r.png", "", "r.png");
  with("ramp is a folder", ramp, "r.png/x", "", "r.png");
  with("ramp missing", ramp, "other.png", "", "r.png");

  const json style = {{"style", {{"preset", "p.json"}}}};
  for (const std::string& text :
       {std::string("{\"width\": -1}"), std::string("{\"colour\": 1}"), std::string("{"),
        "{\"hair_color\": " + std::string(10000, '[') + std::string(10000, ']') + "}",
        std::string("{\"preset\": \"toon\"}"), std::string("{\"width\": 1e300}"),
        std::string("{\"shading\": {\"ramp\": \"none.png\"}}"), std::string("{\"ink\": 3}")})
    with("style " + text.substr(0, 24), style, "p.json", text, "p.json");
  with("style is a folder", style, "p.json/x", "", "p.json");
  return cases;
}

std::vector<Case> drawing_cases() {
  std::vector<Case> cases;
  const std::string diffuse = kWisp + " diffuse {d}/in.xml -o {d}/out.png";
  const auto add = [&](const std::string& name, const std::string& xml) {
    cases.push_back({name, {{"in.xml", xml}}, diffuse, "in.xml"});
  };
  for (const char* p : {"x=\"1e300\" y=\"256\"", "x=\"1e30\" y=\"256\"", "x=\"-1e12\" y=\"256\"",
                        "x=\"256\" y=\"1e20\"", "x=\"nan\" y=\"256\"", "x=\"inf\" y=\"256\"",
                        "x=\"abc\" y=\"256\"", "y=\"256\"", "x=\"40000\" y=\"256\""})
    add(std::string("control point ") + p, drawing(p));
  const std::string circle = read(WISP_SOURCE_DIR "/data/drawings/circle.xml");
  add("image size 0", replace_all(circle, "image_width=\"512\"", "image_width=\"0\""));
  add("image size 1e6", replace_all(circle, "image_width=\"512\"", "image_width=\"1000000\""));
  add("negative colour", replace_all(circle, "R=\"255\" G=\"200\"", "R=\"-5\" G=\"200\""));
  add("huge blur", replace_all(circle, "value=\"", "value=\"1e300"));
  add("truncated", circle.substr(0, circle.size() / 2));
  add("not XML", "hello");
  add("empty", "");
  add("unknown doctype", "<!DOCTYPE Other>\n<scene/>");
  add("wrong root", "<svg/>");
  add("nested deep", std::string("<scene image_width=\"9\" image_height=\"9\">") +
                         replace_all(std::string(3000, '.'), ".", "<a>") + "</scene>");
  add("3 control points",
      replace_all(circle, "nb_control_points=\"13\"", "nb_control_points=\"3\""));
  cases.push_back({"drawing is a folder", {{"in.xml/x", ""}}, diffuse, "in.xml"});
  cases.push_back({"drawing missing", {}, diffuse, "in.xml"});
  const std::string good = read(WISP_SOURCE_DIR "/data/drawings/circle.xml");
  const auto option = [&](const std::string& name, const std::string& extra,
                          const std::string& named) {
    cases.push_back({name, {{"in.xml", good}}, diffuse + " " + extra, named});
  };
  option("--stats in a missing folder", "--stats {d}/none/s.json", "--stats");
  option("--stats under a file", "--stats {d}/in.xml/s.json", "--stats");
  option("--xml in a missing folder", "--xml {d}/none/d.xml", "--xml");
  option("--size 0x0", "--size 0x0", "--size");
  option("--size 100000x10", "--size 100000x10", "--size");
  option("--scale 1000", "--scale 1000", "--scale");
  cases.push_back({"-o in a missing folder",
                   {{"in.xml", good}},
                   kWisp + " diffuse {d}/in.xml -o {d}/none/out.png",
                   "out.png"});
  cases.push_back({"-o is a folder",
                   {{"in.xml", good}, {"o.png/x", ""}},
                   kWisp + " diffuse {d}/in.xml -o {d}/o.png",
                   "o.png"});
  return cases;
}

std::vector<Case> render_cases() {
  std::vector<Case> cases;
  const std::string scene = tiny_scene().dump();
  const std::string render = kWisp + " render {d}/scene.json -o {d}/out -q";
  const auto add = [&](const std::string& name, const std::string& extra,
                       const std::map<std::string, std::string>& files, const std::string& named) {
    std::map<std::string, std::string> all = files;
    all.emplace("scene.json", scene);
    cases.push_back({name, all, render + " " + extra, named});
  };
  add("--anim missing", "--anim {d}/none.wsim", {}, "none.wsim");
  add("--anim is a folder", "--anim {d}/a.wsim", {{"a.wsim/x", ""}}, "a.wsim");
  add("--anim truncated", "--anim {d}/a.wsim", {{"a.wsim", animation().substr(0, 100)}}, "a.wsim");
  add("--anim not a wsim", "--anim {d}/a.wsim", {{"a.wsim", "hello"}}, "a.wsim");
  add("--anim corrupt", "--anim {d}/a.wsim",
      {{"a.wsim",
        [] {
          std::string b = animation();
          b[b.size() / 2] ^= 1;
          return b;
        }()}},
      "a.wsim");
  for (double fps : {std::nan(""), 0.0, 1e308, -24.0})
    add("--anim fps " + std::to_string(fps), "--anim {d}/a.wsim",
        {{"a.wsim", animation([&](std::string& b) { poke(b, 12, fps); })}}, "a.wsim");
  add("--anim version 9", "--anim {d}/a.wsim",
      {{"a.wsim", animation([](std::string& b) { poke(b, 4, std::uint32_t(9)); })}}, "a.wsim");
  add("--anim mesh head without triangles", "--anim {d}/a.wsim",
      {{"a.wsim",
        [] {
          // Head shape 1 (mesh) with 0 vertices and 0 triangles: the tiny scene's 3 strands
          // come first (4 + 4 + 4 + 8 + 4 + 4 + 3 x 4 bytes).
          return animation([](std::string& b) { poke(b, 40, std::uint32_t(1)); });
        }()}},
      "a.wsim");
  add("--anim huge strand sample", "--anim {d}/a.wsim",
      {{"a.wsim", animation([](std::string& b) { poke(b, b.size() - 40, 1e300); })}}, "a.wsim");
  add("--frames 5:2", "--frames 5:2", {}, "--frames");
  add("--frames x", "--frames x", {}, "--frames");
  add("--frames past the end", "--frames 0:999", {}, "--frames");
  add("--size 0x5", "--size 0x5", {}, "--size");
  add("--size 99999x10", "--size 99999x10", {}, "--size");
  add("--size 16384x16384 (memory)", "--size 16384x16384", {}, "--size");
  add("--size 16384x1 (video)", "--size 16384x1", {}, "--size");
  add("--max-memory too small", "--max-memory 0.01", {}, "--max-memory");
  add("-o is a file", "", {{"out", "x"}}, "out");
  add("-o under a file", "", {}, "scene.json");
  cases.back().command = kWisp + " render {d}/scene.json -o {d}/scene.json/out -q";
  add("scene budget before the folder", "", {}, "scene.json");
  cases.back().files["scene.json"] = R"({"hair": {"count": 100000, "segments": 1000}})";
  add("camera 65536", "", {}, "scene.json");
  cases.back().files["scene.json"] = R"({"camera": {"width": 65536, "height": 65536}})";
  add("fps 1e308 in the scene", "", {}, "scene.json");
  cases.back().files["scene.json"] = R"({"sim": {"fps": 1e308}})";
  cases.push_back({"simulate -o in a missing folder",
                   {{"scene.json", scene}},
                   kWisp + " simulate {d}/scene.json -o {d}/none/a.wsim -q",
                   "a.wsim"});
  cases.push_back({"inspect deep JSON",
                   {{"scene.json", std::string(50000, '[') + std::string(50000, ']')}},
                   kInspect + " {d}/scene.json --size 32x32 --snapshot {d}/s.png",
                   "scene.json"});
  cases.push_back({"inspect scene folder",
                   {{"scene.json/x", ""}},
                   kInspect + " {d}/scene.json --size 32x32 --snapshot {d}/s.png",
                   "scene.json"});
  return cases;
}

void run_all(const std::vector<Case>& cases, int first_index) {
  for (std::size_t i = 0; i < cases.size(); ++i) run_case(cases[i], first_index + int(i));
}

}  // namespace

TEST_CASE("survey: the table holds at least 150 bad inputs", "[cli][survey]") {
  const std::size_t total =
      scene_cases().size() + file_cases().size() + drawing_cases().size() + render_cases().size();
  CHECK(total >= 150);
}

TEST_CASE("survey: bad scenes are refused cleanly", "[cli][survey]") {
  run_all(scene_cases(), 0);
}

TEST_CASE("survey: bad strand, head, ramp and style files are refused cleanly", "[cli][survey]") {
  run_all(file_cases(), 1000);
}

TEST_CASE("survey: bad drawings and diffuse options are refused cleanly", "[cli][survey]") {
  run_all(drawing_cases(), 2000);
}

TEST_CASE("survey: bad animations and render options are refused cleanly", "[cli][survey]") {
  run_all(render_cases(), 3000);
}
