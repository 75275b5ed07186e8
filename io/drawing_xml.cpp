// Diffusion-curve XML reader and writer (see drawing_xml.hpp).
#include "io/drawing_xml.hpp"

#include <tinyxml2.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "io/atomic_file.hpp"
#include "io/input_file.hpp"

namespace wisp::io {
namespace {

using diffusion::BlurStop;
using diffusion::Boundary;
using diffusion::Color;
using diffusion::ColorStop;
using diffusion::DiffusionCurve;
using diffusion::GradientMesh;
using diffusion::PoissonCurve;
using tinyxml2::XMLElement;

// Input text for a message: in quotes, on one line (anything outside printable ASCII shown as
// '?'), cut after 40 characters.
std::string quoted(const std::string& value) {
  std::string q;
  for (const char c : value.substr(0, 40)) q += c >= ' ' && c <= '~' ? c : '?';
  return "\"" + q + (value.size() > 40 ? "...\"" : "\"");
}

class Reader {
 public:
  Reader(std::string name, XmlDialect dialect) : name_(std::move(name)), dialect_(dialect) {}

  [[noreturn]] void fail(const XMLElement* e, const std::string& what) const {
    throw std::invalid_argument(name_ + ":" + std::to_string(e ? e->GetLineNum() : 0) + ": <" +
                                (e ? e->Name() : "?") + ">: " + what);
  }

  double number(const XMLElement* e, const char* attr) const {
    const char* text = e->Attribute(attr);
    if (!text) fail(e, std::string("missing attribute '") + attr + "'");
    double v = 0;
    if (e->QueryDoubleAttribute(attr, &v) != tinyxml2::XML_SUCCESS || !std::isfinite(v))
      fail(e, std::string("attribute '") + attr + "' is not a finite number: " + quoted(text));
    return v;
  }

  int count(const XMLElement* e, const char* attr) const {
    const double v = number(e, attr);
    if (v < 0 || v != std::floor(v) || v > 1e8)
      fail(e, std::string("attribute '") + attr + "' must be a count, got " + e->Attribute(attr));
    return int(v);
  }

  // Checks an optional nb_* attribute against the number of children actually present. A wrong
  // control-point count means corrupt geometry: an error. Published drawings often carry stale
  // colour or blur counts (two of small-usvg's demo scenes do); those are warnings, and the
  // elements present are used.
  void check_count(const XMLElement* e, const char* attr, size_t actual, bool fatal) const {
    if (!e->Attribute(attr)) return;
    const int declared = count(e, attr);
    if (size_t(declared) == actual) return;
    const std::string what = std::string(attr) + "=" + std::to_string(declared) + " but " +
                             std::to_string(actual) + " are present";
    if (fatal) fail(e, what);
    warnings_.push_back(name_ + ":" + std::to_string(e->GetLineNum()) + ": <" + e->Name() +
                        ">: " + what + " (using the " + std::to_string(actual) + ")");
  }

  // A colour, or with `weight` a Poisson weight: the same attributes, of any sign.
  Color color(const XMLElement* e, bool weight = false) const {
    Color c;
    const bool bytes = e->Attribute("R") || e->Attribute("G") || e->Attribute("B");
    const char* names[3] = {bytes ? "R" : "r", bytes ? "G" : "g", bytes ? "B" : "b"};
    const double top = bytes ? 255.0 : 1.0;
    for (int k = 0; k < 3; ++k) {
      const double v = number(e, names[k]);
      if (!weight && (v < 0 || v > top))
        fail(e, std::string("colour '") + names[k] + "' must lie in [0," + (bytes ? "255" : "1") +
                    "], got " + e->Attribute(names[k]));
      c[k] = float(v / top);
    }
    if (dialect_ == XmlDialect::CurveSetXML) std::swap(c[0], c[2]);  // the files store BGR
    return c;
  }

  // The control points of a cubic Bezier path under `e`, checked against nb_control_points.
  std::vector<Eigen::Vector2d> path(const XMLElement* e, const std::string& what) const {
    std::vector<Eigen::Vector2d> points;
    const XMLElement* set = e->FirstChildElement("control_points_set");
    if (!set) fail(e, "missing <control_points_set>");
    for (const XMLElement* p = set->FirstChildElement("control_point"); p;
         p = p->NextSiblingElement("control_point")) {
      const double x = number(p, "x"), y = number(p, "y");
      points.push_back(on_canvas(
          p, dialect_ == XmlDialect::CurveSetXML ? Eigen::Vector2d(y, x) : Eigen::Vector2d(x, y)));
    }
    check_count(e, "nb_control_points", points.size(), true);
    const size_t n = points.size();
    if (n < 4 || (n - 1) % 3 != 0)
      fail(e, what + " has " + std::to_string(n) +
                  " control points; a cubic Bezier path needs 3k+1 (4, 7, 10, ...)");
    return points;
  }

  // The children named `child` of element `set` (which may be null) with their globalID
  // normalised: divided by the set's largest globalID when that exceeds 1.
  template <class Stop, class Make>
  std::vector<Stop> stops(const XMLElement* set, const char* child, Make make) const {
    std::vector<Stop> out;
    if (!set) return out;
    std::vector<const XMLElement*> elements;
    for (const XMLElement* e = set->FirstChildElement(child); e; e = e->NextSiblingElement(child))
      elements.push_back(e);
    double largest = 0;
    for (const XMLElement* e : elements) {
      const double id = number(e, "globalID");
      if (id < 0) fail(e, "globalID must be >= 0");
      largest = std::max(largest, id);
    }
    for (const XMLElement* e : elements) {
      Stop s = make(e);
      s.t = number(e, "globalID") / (largest > 1 ? largest : 1.0);
      out.push_back(s);
    }
    std::stable_sort(out.begin(), out.end(),
                     [](const Stop& a, const Stop& b) { return a.t < b.t; });
    return out;
  }

  Boundary boundary(const XMLElement* set) const {
    if (!set) return Boundary::Dirichlet;
    const char* b = set->Attribute("boundary");
    if (!b || std::string(b) == "Dirichlet") return Boundary::Dirichlet;
    if (std::string(b) == "Neumann") return Boundary::Neumann;
    fail(set, "boundary must be \"Dirichlet\" or \"Neumann\", got " + quoted(b));
  }

  DiffusionCurve curve(const XMLElement* e, int index) const {
    DiffusionCurve c;
    c.points = path(e, "curve " + std::to_string(index));

    const XMLElement* left = e->FirstChildElement("left_colors_set");
    const XMLElement* right = e->FirstChildElement("right_colors_set");
    const auto make_color = [&](const XMLElement* s) { return ColorStop{0, color(s)}; };
    c.left = stops<ColorStop>(left, "left_color", make_color);
    c.right = stops<ColorStop>(right, "right_color", make_color);
    check_count(e, "nb_left_colors", c.left.size(), false);
    check_count(e, "nb_right_colors", c.right.size(), false);
    c.left_boundary = boundary(left);
    c.right_boundary = boundary(right);
    if (c.left.empty() && c.left_boundary == Boundary::Dirichlet)
      fail(e, "the left colour set is empty (give colours or boundary=\"Neumann\")");
    if (c.right.empty() && c.right_boundary == Boundary::Dirichlet)
      fail(e, "the right colour set is empty (give colours or boundary=\"Neumann\")");
    if (dialect_ == XmlDialect::CurveSetXML) {
      // The x/y swap mirrors the picture, which exchanges the sides.
      std::swap(c.left, c.right);
      std::swap(c.left_boundary, c.right_boundary);
    }
    const XMLElement* blur = e->FirstChildElement("blur_points_set");
    c.blur = stops<BlurStop>(blur, "best_scale", [&](const XMLElement* s) {
      const double v = number(s, "value");
      if (v < 0 || v > std::max(width_, height_))
        fail(s, "blur value must be in [0, " + std::to_string(std::max(width_, height_)) +
                    "] (the image's larger side)");
      return BlurStop{0, float(v)};
    });
    check_count(e, "nb_blur_points", c.blur.size(), false);
    diffusion::validate(
        c, name_ + ":" + std::to_string(e->GetLineNum()) + ": curve " + std::to_string(index));
    return c;
  }

  PoissonCurve poisson_curve(const XMLElement* e, int index) const {
    const std::string what = "Poisson curve " + std::to_string(index);
    PoissonCurve c;
    c.points = path(e, what);
    const XMLElement* weights = e->FirstChildElement("weights_set");
    if (!weights) fail(e, "missing <weights_set>");
    c.weights = stops<ColorStop>(weights, "weight", [&](const XMLElement* w) {
      return ColorStop{0, color(w, true)};
    });
    check_count(e, "nb_weights", c.weights.size(), false);
    if (c.weights.empty()) fail(weights, what + " has no <weight>");
    diffusion::validate(c, name_ + ":" + std::to_string(e->GetLineNum()) + ": " + what);
    return c;
  }

  // The children `child` of `e`'s element `set`, as points (x, y).
  std::vector<Eigen::Vector2d> points(const XMLElement* set, const char* child) const {
    std::vector<Eigen::Vector2d> out;
    for (const XMLElement* p = set->FirstChildElement(child); p; p = p->NextSiblingElement(child))
      out.push_back(on_canvas(p, Eigen::Vector2d(number(p, "x"), number(p, "y"))));
    return out;
  }

  GradientMesh mesh(const XMLElement* e, int index) const {
    const std::string what = "gradient mesh " + std::to_string(index);
    GradientMesh m;
    m.rows = count(e, "nb_rows");
    m.cols = count(e, "nb_cols");
    if (m.rows < 1 || m.cols < 1) fail(e, what + " needs nb_rows and nb_cols of at least 1");
    if (const char* n = e->Attribute("normalized")) {
      const std::string v = n;
      if (v == "1" || v == "true")
        m.normalized = true;
      else if (v != "0" && v != "false")
        fail(e, "normalized must be 0, 1, true or false, got " + quoted(v));
    }
    const size_t vertices = size_t(m.rows + 1) * size_t(m.cols + 1);
    const auto expect = [&](const XMLElement* at, size_t got, const char* what_set) {
      if (got != vertices)
        fail(at, what + ": " + std::to_string(got) + " " + what_set + " for " +
                     std::to_string(m.rows) + "x" + std::to_string(m.cols) + " tiles; expected " +
                     std::to_string(vertices));
    };
    const XMLElement* positions = e->FirstChildElement("position_set");
    if (!positions) fail(e, "missing <position_set>");
    m.positions = points(positions, "position");
    check_count(e, "nb_positions", m.positions.size(), true);
    expect(positions, m.positions.size(), "positions");
    const XMLElement* colors = e->FirstChildElement("color_set");
    if (!colors) fail(e, "missing <color_set>");
    for (const XMLElement* c = colors->FirstChildElement("color"); c;
         c = c->NextSiblingElement("color"))
      m.colors.push_back(color(c));
    check_count(e, "nb_colors", m.colors.size(), true);
    expect(colors, m.colors.size(), "colours");
    // small-usvg reads <pos_tangent_set> only (one published mesh spells it pos_tangents_set,
    // and is drawn with estimated tangents): so do we.
    if (const XMLElement* t = e->FirstChildElement("pos_tangent_set")) {
      m.tangents_u = points(t, "positionU");
      m.tangents_v = points(t, "positionV");
      expect(t, m.tangents_u.size(), "<positionU>");
      expect(t, m.tangents_v.size(), "<positionV>");
    }
    diffusion::validate(m, name_ + ":" + std::to_string(e->GetLineNum()) + ": " + what);
    return m;
  }

  DrawingFile read(const tinyxml2::XMLDocument& doc) {
    DrawingFile out;
    out.dialect = dialect_;
    const XMLElement* root = doc.RootElement();
    const char* expected = dialect_ == XmlDialect::SceneXML ? "scene" : "curve_set";
    if (!root || std::string(root->Name()) != expected)
      fail(root, std::string("the root element must be <") + expected + ">");
    const int w = count(root, "image_width"), h = count(root, "image_height");
    if (w < 1 || h < 1 || w > kMaxImageSide || h > kMaxImageSide)
      fail(root, "image size " + std::to_string(w) + "x" + std::to_string(h) +
                     " must be between 1 and " + std::to_string(kMaxImageSide));
    out.drawing.width = width_ = w;
    out.drawing.height = height_ = h;

    const XMLElement* set =
        dialect_ == XmlDialect::SceneXML ? root->FirstChildElement("curve_set") : root;
    if (set) {
      int index = 0;
      for (const XMLElement* c = set->FirstChildElement("curve"); c;
           c = c->NextSiblingElement("curve"))
        out.drawing.curves.push_back(curve(c, ++index));
      check_count(set, "nb_curves", out.drawing.curves.size(), true);
    }
    if (dialect_ == XmlDialect::SceneXML) {
      if (const XMLElement* pset = root->FirstChildElement("poisson_curve_set")) {
        int index = 0;
        for (const XMLElement* c = pset->FirstChildElement("poisson_curve"); c;
             c = c->NextSiblingElement("poisson_curve"))
          out.drawing.poisson_curves.push_back(poisson_curve(c, ++index));
        check_count(pset, "nb_curves", out.drawing.poisson_curves.size(), true);
      }
      if (const XMLElement* mset = root->FirstChildElement("mesh_set")) {
        int index = 0;
        for (const XMLElement* m = mset->FirstChildElement("mesh"); m;
             m = m->NextSiblingElement("mesh"))
          out.drawing.meshes.push_back(mesh(m, ++index));
        check_count(mset, "nb_meshes", out.drawing.meshes.size(), true);
      }
    }
    out.warnings = warnings_;
    return out;
  }

 private:
  // Points within kReach image sides of the image: every primitive is drawn at most that far out,
  // however the drawing is scaled, so scaled coordinates stay far from integer overflow.
  static constexpr double kReach = 64;
  Eigen::Vector2d on_canvas(const XMLElement* e, const Eigen::Vector2d& p) const {
    if (std::abs(p.x()) > kReach * width_ || std::abs(p.y()) > kReach * height_)
      fail(e, "point (" + fmt_number(p.x()) + ", " + fmt_number(p.y()) + ") lies more than " +
                  std::to_string(int(kReach)) + " image sides outside the " +
                  std::to_string(width_) + "x" + std::to_string(height_) + " image");
    return p;
  }
  static std::string fmt_number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
  }

  std::string name_;
  XmlDialect dialect_;
  int width_ = 1, height_ = 1;
  mutable std::vector<std::string> warnings_;
};

// The DOCTYPE decides the dialect; without one, the root element's name does.
XmlDialect detect_dialect(const tinyxml2::XMLDocument& doc, const std::string& name) {
  for (const tinyxml2::XMLNode* n = doc.FirstChild(); n; n = n->NextSibling()) {
    if (const tinyxml2::XMLUnknown* u = n->ToUnknown()) {
      const std::string v = u->Value();
      if (v.find("SceneXML") != std::string::npos) return XmlDialect::SceneXML;
      if (v.find("CurveSetXML") != std::string::npos) return XmlDialect::CurveSetXML;
      throw std::invalid_argument(name + ":" + std::to_string(u->GetLineNum()) +
                                  ": unknown document type " + quoted("<!" + v + ">") +
                                  "; expected CurveSetXML or SceneXML");
    }
    if (n->ToElement()) break;
  }
  const XMLElement* root = doc.RootElement();
  if (root && std::string(root->Name()) == "scene") return XmlDialect::SceneXML;
  if (root && std::string(root->Name()) == "curve_set") return XmlDialect::CurveSetXML;
  throw std::invalid_argument(
      name +
      ": not a diffusion-curve drawing (no <!DOCTYPE CurveSetXML> "
      "or <!DOCTYPE SceneXML>, and the root is not <curve_set> or <scene>)");
}

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

}  // namespace

DrawingFile parse_drawing_xml(const std::string& text, const std::string& name) {
  tinyxml2::XMLDocument doc;
  if (doc.Parse(text.data(), text.size()) != tinyxml2::XML_SUCCESS)
    throw std::invalid_argument(name + ":" + std::to_string(doc.ErrorLineNum()) +
                                ": malformed XML: " + doc.ErrorName());
  return Reader(name, detect_dialect(doc, name)).read(doc);
}

DrawingFile read_drawing_xml(const std::filesystem::path& path) {
  return parse_drawing_xml(read_input_file(path, "drawing file"), path.string());
}

std::string format_drawing_xml(const diffusion::Drawing& d, XmlDialect dialect) {
  const bool orzan = dialect == XmlDialect::CurveSetXML;
  if (orzan && (!d.poisson_curves.empty() || !d.meshes.empty()))
    throw std::invalid_argument(
        "CurveSetXML cannot hold Poisson curves or gradient meshes; write SceneXML");
  std::ostringstream o;
  const std::string size = "image_width=\"" + std::to_string(d.width) + "\" image_height=\"" +
                           std::to_string(d.height) + "\"";
  const std::string nb = "nb_curves=\"" + std::to_string(d.curves.size()) + "\"";
  if (orzan) {
    o << "<!DOCTYPE CurveSetXML>\n<curve_set " << size << " " << nb << ">\n";
  } else {
    o << "<!DOCTYPE SceneXML>\n<scene " << size << ">\n <curve_set " << nb << ">\n";
  }
  const auto id = [&](double t) {
    return orzan ? fmt("%.0f", std::round(t * 10000)) : fmt("%.17g", t);
  };
  const auto colour = [&](const Color& c) {
    if (orzan)  // BGR bytes
      return "R=\"" + fmt("%.0f", std::round(c[2] * 255)) + "\" G=\"" +
             fmt("%.0f", std::round(c[1] * 255)) + "\" B=\"" + fmt("%.0f", std::round(c[0] * 255)) +
             "\"";
    return "r=\"" + fmt("%.9g", c[0]) + "\" g=\"" + fmt("%.9g", c[1]) + "\" b=\"" +
           fmt("%.9g", c[2]) + "\"";
  };
  for (const DiffusionCurve& c : d.curves) {
    // In CurveSetXML our left side is the file's right side (see the reader).
    const auto& first = orzan ? c.right : c.left;
    const auto& second = orzan ? c.left : c.right;
    const Boundary first_b = orzan ? c.right_boundary : c.left_boundary;
    const Boundary second_b = orzan ? c.left_boundary : c.right_boundary;
    o << "  <curve nb_control_points=\"" << c.points.size() << "\" nb_left_colors=\""
      << first.size() << "\" nb_right_colors=\"" << second.size() << "\" nb_blur_points=\""
      << c.blur.size() << "\">\n   <control_points_set>\n";
    for (const Eigen::Vector2d& p : c.points) {
      const double x = orzan ? p.y() : p.x(), y = orzan ? p.x() : p.y();
      o << "    <control_point x=\"" << fmt("%.17g", x) << "\" y=\"" << fmt("%.17g", y) << "\"/>\n";
    }
    o << "   </control_points_set>\n";
    const auto set = [&](const char* tag, const char* item, const std::vector<ColorStop>& stops,
                         Boundary b) {
      o << "   <" << tag << (b == Boundary::Neumann ? " boundary=\"Neumann\"" : "") << ">\n";
      for (const ColorStop& s : stops)
        o << "    <" << item << " " << colour(s.color) << " globalID=\"" << id(s.t) << "\"/>\n";
      o << "   </" << tag << ">\n";
    };
    set("left_colors_set", "left_color", first, first_b);
    set("right_colors_set", "right_color", second, second_b);
    o << "   <blur_points_set>\n";
    for (const BlurStop& s : c.blur)
      o << "    <best_scale value=\"" << fmt("%.9g", s.sigma) << "\" globalID=\"" << id(s.t)
        << "\"/>\n";
    o << "   </blur_points_set>\n  </curve>\n";
  }
  if (orzan) {
    o << "</curve_set>\n";
    return o.str();
  }
  o << " </curve_set>\n";
  const auto point = [&](const char* tag, const Eigen::Vector2d& p) {
    o << "    <" << tag << " x=\"" << fmt("%.17g", p.x()) << "\" y=\"" << fmt("%.17g", p.y())
      << "\"/>\n";
  };
  if (!d.poisson_curves.empty()) {
    o << " <poisson_curve_set nb_curves=\"" << d.poisson_curves.size() << "\">\n";
    for (const PoissonCurve& c : d.poisson_curves) {
      o << "  <poisson_curve nb_control_points=\"" << c.points.size() << "\" nb_weights=\""
        << c.weights.size() << "\">\n   <control_points_set>\n";
      for (const Eigen::Vector2d& p : c.points) point("control_point", p);
      o << "   </control_points_set>\n   <weights_set>\n";
      for (const ColorStop& s : c.weights)
        o << "    <weight " << colour(s.color) << " globalID=\"" << id(s.t) << "\"/>\n";
      o << "   </weights_set>\n  </poisson_curve>\n";
    }
    o << " </poisson_curve_set>\n";
  }
  if (!d.meshes.empty()) {
    o << " <mesh_set nb_meshes=\"" << d.meshes.size() << "\">\n";
    for (const GradientMesh& m : d.meshes) {
      o << "  <mesh nb_rows=\"" << m.rows << "\" nb_cols=\"" << m.cols << "\" nb_positions=\""
        << m.positions.size() << "\" nb_colors=\"" << m.colors.size() << "\" normalized=\""
        << (m.normalized ? 1 : 0) << "\">\n   <position_set>\n";
      for (const Eigen::Vector2d& p : m.positions) point("position", p);
      o << "   </position_set>\n   <color_set>\n";
      for (const Color& c : m.colors) o << "    <color " << colour(c) << "/>\n";
      o << "   </color_set>\n";
      if (!m.tangents_u.empty()) {
        o << "   <pos_tangent_set>\n";
        for (size_t k = 0; k < m.tangents_u.size(); ++k) {
          point("positionU", m.tangents_u[k]);
          point("positionV", m.tangents_v[k]);
        }
        o << "   </pos_tangent_set>\n";
      }
      o << "  </mesh>\n";
    }
    o << " </mesh_set>\n";
  }
  o << "</scene>\n";
  return o.str();
}

void write_drawing_xml(const diffusion::Drawing& drawing, const std::filesystem::path& path,
                       XmlDialect dialect) {
  const std::string text = format_drawing_xml(drawing, dialect);
  write_text_atomically(path, text);
}

}  // namespace wisp::io
