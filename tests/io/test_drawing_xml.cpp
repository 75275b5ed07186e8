// Diffusion-curve XML: both dialects, their swaps, round trips, and clear errors.

#include <catch2/catch.hpp>
#include <filesystem>
#include <map>

#include "io/drawing_xml.hpp"
#include "tests/test_folder.hpp"

using namespace wisp;
using diffusion::Boundary;

namespace {

const std::string kData = WISP_SOURCE_DIR "/data/drawings/external/";

bool same_stops(const std::vector<diffusion::ColorStop>& a,
                const std::vector<diffusion::ColorStop>& b) {
  if (a.size() != b.size()) return false;
  for (size_t k = 0; k < a.size(); ++k)
    if (a[k].t != b[k].t || a[k].color != b[k].color) return false;
  return true;
}

// Every primitive, compared exactly.
bool same_curves(const diffusion::Drawing& a, const diffusion::Drawing& b) {
  if (a.width != b.width || a.height != b.height || a.curves.size() != b.curves.size() ||
      a.poisson_curves.size() != b.poisson_curves.size() || a.meshes.size() != b.meshes.size())
    return false;
  for (size_t i = 0; i < a.poisson_curves.size(); ++i) {
    const auto &p = a.poisson_curves[i], &q = b.poisson_curves[i];
    if (p.points != q.points || !same_stops(p.weights, q.weights)) return false;
  }
  for (size_t i = 0; i < a.meshes.size(); ++i) {
    const auto &p = a.meshes[i], &q = b.meshes[i];
    if (p.rows != q.rows || p.cols != q.cols || p.normalized != q.normalized ||
        p.positions != q.positions || p.colors != q.colors || p.tangents_u != q.tangents_u ||
        p.tangents_v != q.tangents_v)
      return false;
  }
  for (size_t i = 0; i < a.curves.size(); ++i) {
    const auto &p = a.curves[i], &q = b.curves[i];
    if (p.points != q.points || p.left_boundary != q.left_boundary ||
        p.right_boundary != q.right_boundary || p.left.size() != q.left.size() ||
        p.right.size() != q.right.size() || p.blur.size() != q.blur.size())
      return false;
    for (size_t k = 0; k < p.left.size(); ++k)
      if (p.left[k].t != q.left[k].t || p.left[k].color != q.left[k].color) return false;
    for (size_t k = 0; k < p.right.size(); ++k)
      if (p.right[k].t != q.right[k].t || p.right[k].color != q.right[k].color) return false;
    for (size_t k = 0; k < p.blur.size(); ++k)
      if (p.blur[k].t != q.blur[k].t || p.blur[k].sigma != q.blur[k].sigma) return false;
  }
  return true;
}

std::string curve_set(const std::string& curve_body, const std::string& attrs = "") {
  return "<!DOCTYPE CurveSetXML>\n<curve_set image_width=\"100\" image_height=\"50\" " + attrs +
         ">\n<curve nb_control_points=\"4\">" + curve_body + "</curve>\n</curve_set>\n";
}

const std::string kPoints =
    "<control_points_set><control_point x=\"10\" y=\"20\"/><control_point x=\"11\" y=\"30\"/>"
    "<control_point x=\"12\" y=\"40\"/><control_point x=\"13\" y=\"50\"/></control_points_set>";
const std::string kColours =
    "<left_colors_set><left_color R=\"255\" G=\"0\" B=\"0\" globalID=\"0\"/>"
    "<left_color R=\"255\" G=\"0\" B=\"0\" globalID=\"40\"/></left_colors_set>"
    "<right_colors_set><right_color R=\"0\" G=\"255\" B=\"0\" globalID=\"0\"/>"
    "<right_color R=\"0\" G=\"128\" B=\"0\" globalID=\"20\"/></right_colors_set>";

}  // namespace

TEST_CASE("all eight small-usvg scenes read, every primitive of them", "[xml]") {
  const std::map<std::string, size_t> curves = {
      {"bubble", 9},   {"crane", 68},  {"crane_ribbons", 62}, {"drape", 87},
      {"ladybug", 59}, {"pepper", 36}, {"portal", 0},         {"sunset", 0}};
  for (const auto& [name, count] : curves) {
    const io::DrawingFile f = io::read_drawing_xml(kData + name + ".xml");
    INFO(name);
    CHECK(f.dialect == io::XmlDialect::SceneXML);
    if (count) CHECK(f.drawing.curves.size() == count);
    CHECK(f.drawing.curves.size() > 0);
    CHECK(f.drawing.width >= 512);
  }
  const io::DrawingFile crane = io::read_drawing_xml(kData + "crane.xml");
  CHECK(crane.warnings.empty());
  REQUIRE(crane.drawing.poisson_curves.size() == 5);
  const auto& pc = crane.drawing.poisson_curves[0];
  CHECK(pc.points.size() == 10);
  REQUIRE(pc.weights.size() == 2);
  CHECK(pc.weights[1].t == 1.0);  // globalID 10 of 10
  CHECK(pc.weights[0].color == diffusion::Color(-0.0375f, -0.0375f, -0.005f));
  REQUIRE(crane.drawing.meshes.size() == 3);
  const auto& m0 = crane.drawing.meshes[0];
  CHECK((m0.rows == 3 && m0.cols == 3 && m0.normalized && m0.positions.size() == 16));
  CHECK(m0.tangents_u.empty());
  const auto& m1 = crane.drawing.meshes[1];
  CHECK((m1.rows == 3 && m1.cols == 4 && !m1.normalized && m1.tangents_v.size() == 20));
  // pepper writes nb_cols="30.000000"; bubble's third mesh spells its tangents pos_tangents_set,
  // which small-usvg does not read either.
  CHECK(io::read_drawing_xml(kData + "pepper.xml").drawing.meshes.at(0).cols == 30);
  CHECK(io::read_drawing_xml(kData + "bubble.xml").drawing.meshes.at(2).tangents_u.empty());
  int neumann = 0;
  for (const auto& c : crane.drawing.curves)
    neumann += (c.left_boundary == Boundary::Neumann) + (c.right_boundary == Boundary::Neumann);
  CHECK(neumann == 28);
}

TEST_CASE("CurveSetXML swaps x/y, R/B and the two sides and normalises globalIDs", "[xml]") {
  const io::DrawingFile f = io::parse_drawing_xml(curve_set(kPoints + kColours), "t.xml");
  CHECK(f.dialect == io::XmlDialect::CurveSetXML);
  const auto& c = f.drawing.curves.at(0);
  CHECK(c.points[0] == Eigen::Vector2d(20, 10));  // x is the row
  // The file's left set (R=255: blue, since R holds blue) is our right side.
  REQUIRE(c.right.size() == 2);
  CHECK(c.right[0].color == diffusion::Color(0, 0, 1));
  CHECK(c.right[1].t == 1.0);  // 40 / 40
  REQUIRE(c.left.size() == 2);
  CHECK(c.left[1].t == 1.0);  // 20 / 20: each set by its own largest globalID
  CHECK(c.left[1].color.y() == Approx(128 / 255.0f));
}

TEST_CASE("writing then reading gives identical curves", "[xml]") {
  for (const char* name :
       {"bubble", "crane", "crane_ribbons", "drape", "ladybug", "pepper", "portal", "sunset"}) {
    INFO(name);
    const io::DrawingFile a = io::read_drawing_xml(kData + name + ".xml");
    const io::DrawingFile b =
        io::parse_drawing_xml(io::format_drawing_xml(a.drawing, io::XmlDialect::SceneXML), "b");
    CHECK(same_curves(a.drawing, b.drawing));
  }
  // The original format rounds colours to bytes and globalIDs to 1e-4, nothing else.
  const io::DrawingFile a = io::parse_drawing_xml(curve_set(kPoints + kColours), "t.xml");
  const io::DrawingFile b =
      io::parse_drawing_xml(io::format_drawing_xml(a.drawing, io::XmlDialect::CurveSetXML), "b");
  CHECK(b.dialect == io::XmlDialect::CurveSetXML);
  CHECK(same_curves(a.drawing, b.drawing));
  // Which cannot hold small-usvg's primitives.
  CHECK_THROWS_WITH(io::format_drawing_xml(io::read_drawing_xml(kData + "crane.xml").drawing,
                                           io::XmlDialect::CurveSetXML),
                    Catch::Contains("CurveSetXML cannot hold"));
}

TEST_CASE("files are written whole through a temporary name", "[xml]") {
  const auto dir = wisp::test::test_folder("drawing_xml");
  const io::DrawingFile a = io::read_drawing_xml(kData + "bubble.xml");
  io::write_drawing_xml(a.drawing, dir / "out.xml");
  CHECK(same_curves(io::read_drawing_xml(dir / "out.xml").drawing, a.drawing));
  for (const auto& e : std::filesystem::directory_iterator(dir))
    CHECK(e.path().filename() == "out.xml");
  CHECK_THROWS_WITH(io::write_drawing_xml(a.drawing, dir / "missing" / "out.xml"),
                    Catch::Contains("does not exist"));
  std::filesystem::remove_all(dir);
}

TEST_CASE("bad drawings fail with the file, line and element named", "[xml]") {
  const auto fails = [](const std::string& text, const std::string& expected) {
    CHECK_THROWS_WITH(io::parse_drawing_xml(text, "bad.xml"),
                      Catch::Contains("bad.xml") && Catch::Contains(expected));
  };
  fails("<!DOCTYPE CurveSetXML>\n<curve_set image_width=\"10\"", "malformed XML");
  fails("<!DOCTYPE Nonsense>\n<x/>", "unknown document type");
  fails("<svg/>", "not a diffusion-curve drawing");
  fails(curve_set(kPoints + kColours, "nb_curves=\"3\""), "nb_curves=3 but 1");
  std::string wrong = curve_set(kPoints + kColours);
  wrong.replace(wrong.find("nb_control_points=\"4\""), 21, "nb_control_points=\"5\"");
  fails(wrong, "nb_control_points=5 but 4");
  std::string nan = curve_set(kPoints + kColours);
  nan.replace(nan.find("x=\"11\""), 6, "x=\"nan\"");
  fails(nan, "<control_point>: attribute 'x' is not a finite number");
  std::string two = curve_set(
      "<control_points_set><control_point x=\"1\" y=\"2\"/>"
      "<control_point x=\"3\" y=\"4\"/></control_points_set>" +
      kColours);
  two.replace(two.find("nb_control_points=\"4\""), 21, "nb_control_points=\"2\"");
  fails(two, "2 control points");
  std::string zero = curve_set(kPoints + kColours);
  zero.replace(zero.find("image_width=\"100\""), 17, "image_width=\"0\"");
  fails(zero, "image size 0x50");
  std::string huge = curve_set(kPoints + kColours);
  huge.replace(huge.find("image_width=\"100\""), 17, "image_width=\"20000\"");
  fails(huge, "16384");
  std::string colour = curve_set(kPoints + kColours);
  colour.replace(colour.find("R=\"255\""), 7, "R=\"300\"");
  fails(colour, "must lie in [0,255]");
  const auto scene = [](const std::string& body) {
    return "<!DOCTYPE SceneXML>\n<scene image_width=\"100\" image_height=\"100\">\n" + body +
           "</scene>\n";
  };
  const std::string pos =
      "<position x=\"0\" y=\"0\"/><position x=\"1\" y=\"0\"/>"
      "<position x=\"0\" y=\"1\"/>";
  fails(scene("<mesh_set><mesh nb_rows=\"1\" nb_cols=\"1\"><position_set>" + pos +
              "</position_set><color_set/></mesh></mesh_set>"),
        "3 positions for 1x1 tiles; expected 4");
  fails(scene("<mesh_set><mesh nb_rows=\"0\" nb_cols=\"1\"/></mesh_set>"),
        "needs nb_rows and nb_cols");
  fails(scene("<poisson_curve_set><poisson_curve>" + kPoints +
              "<weights_set/></poisson_curve></poisson_curve_set>"),
        "Poisson curve 1 has no <weight>");
  CHECK_THROWS_WITH(io::read_drawing_xml("/nonexistent/drawing.xml"),
                    Catch::Contains("/nonexistent/drawing.xml") && Catch::Contains("cannot open"));
}

TEST_CASE("stale colour counts, common in published drawings, are warnings", "[xml]") {
  std::string stale = curve_set(kPoints + kColours);
  stale.replace(stale.find("<curve nb_control_points=\"4\">"), 29,
                "<curve nb_control_points=\"4\" nb_left_colors=\"7\">");
  const io::DrawingFile f = io::parse_drawing_xml(stale, "stale.xml");
  REQUIRE(f.warnings.size() == 1);
  CHECK_THAT(f.warnings[0], Catch::Contains("stale.xml:3") && Catch::Contains("nb_left_colors=7"));
}
