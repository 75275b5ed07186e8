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

namespace wisp::io {
namespace {

using diffusion::BlurStop;
using diffusion::Boundary;
using diffusion::Color;
using diffusion::ColorStop;
using diffusion::DiffusionCurve;
using tinyxml2::XMLElement;

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
      fail(e, std::string("attribute '") + attr + "' is not a finite number: \"" + text + "\"");
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

  Color color(const XMLElement* e) const {
    Color c;
    const bool bytes = e->Attribute("R") || e->Attribute("G") || e->Attribute("B");
    const char* names[3] = {bytes ? "R" : "r", bytes ? "G" : "g", bytes ? "B" : "b"};
    const double top = bytes ? 255.0 : 1.0;
    for (int k = 0; k < 3; ++k) {
      const double v = number(e, names[k]);
      if (v < 0 || v > top)
        fail(e, std::string("colour '") + names[k] + "' must lie in [0," + (bytes ? "255" : "1") +
                    "], got " + e->Attribute(names[k]));
      c[k] = float(v / top);
    }
    if (dialect_ == XmlDialect::CurveSetXML) std::swap(c[0], c[2]);  // the files store BGR
    return c;
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
    fail(set, std::string("boundary must be \"Dirichlet\" or \"Neumann\", got \"") + b + "\"");
  }

  DiffusionCurve curve(const XMLElement* e, int index) const {
    DiffusionCurve c;
    const XMLElement* points = e->FirstChildElement("control_points_set");
    if (!points) fail(e, "missing <control_points_set>");
    for (const XMLElement* p = points->FirstChildElement("control_point"); p;
         p = p->NextSiblingElement("control_point")) {
      const double x = number(p, "x"), y = number(p, "y");
      c.points.emplace_back(dialect_ == XmlDialect::CurveSetXML ? Eigen::Vector2d(y, x)
                                                                : Eigen::Vector2d(x, y));
    }
    check_count(e, "nb_control_points", c.points.size(), true);
    const size_t n = c.points.size();
    if (n < 4 || (n - 1) % 3 != 0)
      fail(e, "curve " + std::to_string(index) + " has " + std::to_string(n) +
                  " control points; a cubic Bezier path needs 3k+1 (4, 7, 10, ...)");

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
      if (v < 0) fail(s, "blur value must be >= 0");
      return BlurStop{0, float(v)};
    });
    check_count(e, "nb_blur_points", c.blur.size(), false);
    diffusion::validate(
        c, name_ + ":" + std::to_string(e->GetLineNum()) + ": curve " + std::to_string(index));
    return c;
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
    out.drawing.width = w;
    out.drawing.height = h;

    const XMLElement* set =
        dialect_ == XmlDialect::SceneXML ? root->FirstChildElement("curve_set") : root;
    if (set) {
      int index = 0;
      for (const XMLElement* c = set->FirstChildElement("curve"); c;
           c = c->NextSiblingElement("curve"))
        out.drawing.curves.push_back(curve(c, ++index));
      check_count(set, "nb_curves", out.drawing.curves.size(), true);
    }
    out.warnings = warnings_;
    if (dialect_ == XmlDialect::SceneXML) {
      const auto skipped = [&](const char* set_name, const char* child, const char* what) {
        const XMLElement* s = root->FirstChildElement(set_name);
        int n = 0;
        for (const XMLElement* e = s ? s->FirstChildElement(child) : nullptr; e;
             e = e->NextSiblingElement(child))
          ++n;
        if (n > 0)
          out.warnings.push_back(name_ + ": skipped " + std::to_string(n) + " " + what +
                                 " (not supported by wisp)");
      };
      skipped("poisson_curve_set", "poisson_curve", "Poisson curve(s)");
      skipped("mesh_set", "mesh", "gradient mesh(es)");
    }
    return out;
  }

 private:
  std::string name_;
  XmlDialect dialect_;
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
                                  ": unknown document type <!" + v +
                                  ">; expected CurveSetXML or SceneXML");
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
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::invalid_argument(path.string() + ": cannot open the file");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_drawing_xml(text.str(), path.string());
}

std::string format_drawing_xml(const diffusion::Drawing& d, XmlDialect dialect) {
  const bool orzan = dialect == XmlDialect::CurveSetXML;
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
  o << (orzan ? "</curve_set>\n" : " </curve_set>\n</scene>\n");
  return o.str();
}

void write_drawing_xml(const diffusion::Drawing& drawing, const std::filesystem::path& path,
                       XmlDialect dialect) {
  const std::string text = format_drawing_xml(drawing, dialect);
  write_text_atomically(path, text);
}

}  // namespace wisp::io
