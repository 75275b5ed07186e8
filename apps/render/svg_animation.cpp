// Frames' SVGs merged into one SMIL animation (see svg_animation.hpp).
#include "apps/render/svg_animation.hpp"

#include <tinyxml2.h>

#include <cstdio>
#include <map>
#include <sstream>
#include <stdexcept>
#include <unordered_map>

#include "io/atomic_file.hpp"
#include "io/input_file.hpp"

namespace wisp::render {
namespace {

using tinyxml2::XMLAttribute;
using tinyxml2::XMLElement;

// Below this many bytes an element is cheaper written again than defined and used.
constexpr std::size_t kShareBytes = 120;

std::string escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '&')
      out += "&amp;";
    else if (c == '<')
      out += "&lt;";
    else if (c == '"')
      out += "&quot;";
    else
      out += c;
  }
  return out;
}

std::string serialize(const XMLElement& e) {
  tinyxml2::XMLPrinter printer(nullptr, true);
  e.Accept(&printer);
  return printer.CStr();
}

// The text with its ids left out: what an element draws, wherever it comes from.
std::string without_ids(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  std::size_t i = 0;
  for (std::size_t p; (p = text.find(" id=\"", i)) != std::string::npos;) {
    out.append(text, i, p - i);
    i = text.find('"', p + 5) + 1;
  }
  return out.append(text, i, std::string::npos);
}

// Ids renamed (`id` + suffix) and references to definitions (url(#x), href="#x") mapped, in e
// and everything inside it.
void rename(XMLElement* e, const std::string& suffix,
            const std::map<std::string, std::string>& defs) {
  for (const XMLAttribute* a = e->FirstAttribute(); a; a = a->Next()) {
    std::string value = a->Value();
    const std::string name = a->Name();
    bool changed = false;
    if (name == "id") {
      value += suffix, changed = true;
    } else if ((name == "xlink:href" || name == "href") && value.size() > 1 && value[0] == '#') {
      const auto it = defs.find(value.substr(1));
      if (it != defs.end()) value = '#' + it->second, changed = true;
    } else {
      for (std::size_t p = 0; (p = value.find("url(#", p)) != std::string::npos;) {
        const std::size_t end = value.find(')', p);
        if (end == std::string::npos) break;
        const auto it = defs.find(value.substr(p + 5, end - p - 5));
        if (it != defs.end()) {
          value.replace(p + 5, end - p - 5, it->second);
          changed = true;
        }
        p += 5;
      }
    }
    if (changed) e->SetAttribute(name.c_str(), value.c_str());
  }
  for (XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement())
    rename(c, suffix, defs);
}

std::string start_tag(const XMLElement& e) {
  std::string out = std::string("<") + e.Name();
  for (const XMLAttribute* a = e.FirstAttribute(); a; a = a->Next())
    out += std::string(" ") + a->Name() + "=\"" + escape(a->Value()) + '"';
  return out + '>';
}

bool hidden(const XMLElement& e) {
  const char* style = e.Attribute("style");
  return style && std::string(style).find("display:none") != std::string::npos;
}

// The frames, merged as they come.
class Animation {
 public:
  void add(const std::string& text, const std::string& name) {
    tinyxml2::XMLDocument doc;
    if (doc.Parse(text.data(), text.size()) != tinyxml2::XML_SUCCESS)
      throw std::runtime_error(name + ": not XML (" + doc.ErrorStr() + ")");
    const XMLElement* root = doc.RootElement();
    if (!root || std::string(root->Name()) != "svg")
      throw std::runtime_error(name + ": not an SVG frame (no <svg> root)");
    const std::string size = std::string(root->Attribute("width") ? root->Attribute("width") : "") +
                             'x' + (root->Attribute("height") ? root->Attribute("height") : "");
    const int k = frames_++;
    if (k == 0) {
      root_tag_ = start_tag(*root);
      size_ = size;
    } else if (size != size_) {
      throw std::runtime_error(name + ": the frame is " + size + ", the first frame " + size_);
    }
    const std::string suffix = "-f" + std::to_string(k);
    std::map<std::string, std::string> def_ids;  // this frame's definition ids -> the document's
    int layers = 0;
    for (XMLElement* e = doc.RootElement()->FirstChildElement(); e; e = e->NextSiblingElement()) {
      const std::string tag = e->Name();
      if (tag == "defs") {
        for (XMLElement* d = e->FirstChildElement(); d; d = d->NextSiblingElement())
          add_definition(d, suffix, def_ids);
      } else if (tag == "g" && e->Attribute("inkscape:groupmode", "layer")) {
        ++layers;
        if (!hidden(*e)) add_layer(e, k, suffix, def_ids);
      }
    }
    if (layers == 0) throw std::runtime_error(name + ": not a wisp frame SVG (no layers)");
  }

  std::string finish(double fps, SvgAnimationStats* stats) {
    // Elements that more than one group holds: into <defs>, used from each.
    std::vector<int> uses(keys_.size(), 0);
    for (const Layer& layer : layers_)
      for (const Group& g : layer.groups)
        for (const Item& item : g.items) ++uses[item.key];
    std::vector<char> defined(keys_.size(), 0);
    std::ostringstream defs, body;
    for (const std::string& d : definitions_) defs << d << '\n';
    int groups = 0, shared = shared_definitions_;
    for (const Layer& layer : layers_) {
      body << layer.tag << '\n';
      for (const Group& g : layer.groups) {
        ++groups;
        body << "<g id=\"" << layer.id << "-f" << g.first << '"'
             << (g.first > 0 ? " display=\"none\"" : "") << ">";
        if (g.first > 0 || g.last < frames_) body << show(g.first, g.last, fps);
        body << '\n';
        for (const Item& item : g.items) {
          const bool share = uses[item.key] > 1 && item.text.size() >= kShareBytes;
          if (!share) {
            body << item.text << '\n';
            continue;
          }
          const std::string def_id = item_id(item, true);
          if (!defined[item.key]) {
            defined[item.key] = 1, ++shared;
            // The first place's text with the shared id.
            std::string text = item.text;
            const std::size_t p = text.find(" id=\"");
            if (p != std::string::npos) text.replace(p, text.find('"', p + 5) + 1 - p, "");
            const std::size_t name_end = text.find_first_of(" />");
            text.insert(name_end, " id=\"" + def_id + '"');
            defs << text << '\n';
            shared_ids_[item.key] = def_id;
          }
          body << "<use id=\"" << item_id(item, false) << "\" xlink:href=\"#"
               << shared_ids_[item.key] << "\"/>\n";
        }
        body << "</g>\n";
      }
      body << "</g>\n";
    }
    std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n" + root_tag_ + "\n<defs>\n" +
                      defs.str() + "</defs>\n" + body.str() + "</svg>\n";
    if (stats) *stats = {frames_, groups, shared, out.size()};
    return out;
  }

  int frames() const { return frames_; }

 private:
  struct Item {
    std::string text;  // with this frame's ids
    int key = 0;       // index of its text without ids
  };
  struct Group {
    int first = 0, last = 0;  // frames first to last - 1
    std::vector<Item> items;
    std::string key;  // the items' keys
  };
  struct Layer {
    std::string id, tag;
    std::vector<Group> groups;
  };

  void add_definition(XMLElement* d, const std::string& suffix,
                      std::map<std::string, std::string>& def_ids) {
    const char* own = d->Attribute("id");
    if (!own) return;  // nothing can refer to it
    const std::string id = own;
    rename(d, suffix, def_ids);
    const std::string text = serialize(*d);
    const auto [it, fresh] = definition_ids_.emplace(without_ids(text), id + suffix);
    if (fresh)
      definitions_.push_back(text);
    else
      ++shared_definitions_;
    def_ids[id] = it->second;
  }

  void add_layer(XMLElement* e, int k, const std::string& suffix,
                 const std::map<std::string, std::string>& def_ids) {
    const std::string id = e->Attribute("id") ? e->Attribute("id") : "layer";
    Layer* layer = nullptr;
    for (Layer& l : layers_)
      if (l.id == id) layer = &l;
    if (!layer) layer = &layers_.emplace_back(Layer{id, start_tag(*e), {}});
    Group group{k, k + 1, {}, {}};
    for (XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
      rename(c, suffix, def_ids);
      std::string text = serialize(*c);
      const auto [it, fresh] = key_index_.emplace(without_ids(text), int(keys_.size()));
      if (fresh) keys_.push_back(it->first.size());
      group.key += std::to_string(it->second) + ',';
      group.items.push_back({std::move(text), it->second});
    }
    // The same as the previous frame: that frame's group lasts one frame longer.
    if (!layer->groups.empty() && layer->groups.back().last == k &&
        layer->groups.back().key == group.key)
      ++layer->groups.back().last;
    else
      layer->groups.push_back(std::move(group));
  }

  // The discrete animation of `display` that shows a group over frames [first, last) of the loop.
  // Inkscape (1.2) knows no SMIL element and warns of each; an empty sodipodi:type (its own
  // attribute naming what a node is to it) makes it keep the node as plain XML, unread and
  // saved back unchanged.
  std::string show(int first, int last, double fps) const {
    const auto time = [&](int f) {
      char buf[32];
      std::snprintf(buf, sizeof buf, "%.6g", double(f) / frames_);
      return std::string(buf);
    };
    std::string values, times;
    if (first > 0) values += "none;", times += "0;";
    values += "inline", times += first > 0 ? time(first) : "0";
    if (last < frames_) values += ";none", times += ';' + time(last);
    char dur[32];
    std::snprintf(dur, sizeof dur, "%.6gs", frames_ / fps);
    return "<animate sodipodi:type=\"\" attributeName=\"display\" values=\"" + values +
           "\" keyTimes=\"" + times + "\" dur=\"" + dur +
           "\" calcMode=\"discrete\" repeatCount=\"indefinite\"/>";
  }

  // An item's id: its own (with its frame), or for the shared copy in <defs>, "-shared" added.
  static std::string item_id(const Item& item, bool shared) {
    const std::size_t p = item.text.find(" id=\"");
    std::string id = p == std::string::npos
                         ? "item-" + std::to_string(item.key)
                         : item.text.substr(p + 5, item.text.find('"', p + 5) - p - 5);
    return shared ? id + "-shared" : id;
  }

  int frames_ = 0;
  std::string root_tag_, size_;
  std::vector<Layer> layers_;
  std::vector<std::string> definitions_;
  std::unordered_map<std::string, std::string> definition_ids_;  // text without ids -> its id
  int shared_definitions_ = 0;
  std::unordered_map<std::string, int> key_index_;  // element text without ids -> key
  std::vector<std::size_t> keys_;                   // per key: its length
  std::map<int, std::string> shared_ids_;
};

}  // namespace

std::string animate_svg_frames(const std::vector<std::string>& frames,
                               const std::vector<std::string>& names, double fps,
                               SvgAnimationStats* stats) {
  if (frames.empty()) throw std::runtime_error("animated SVG: no frames");
  Animation a;
  for (std::size_t i = 0; i < frames.size(); ++i)
    a.add(frames[i], i < names.size() ? names[i] : "frame " + std::to_string(i));
  return a.finish(fps, stats);
}

SvgAnimationStats write_svg_animation(const std::vector<std::filesystem::path>& frames, double fps,
                                      const std::filesystem::path& path) {
  if (frames.empty()) throw std::runtime_error(path.string() + ": no frames to animate");
  Animation a;
  for (const std::filesystem::path& f : frames)
    a.add(io::read_input_file(f, "frame SVG"), f.string());
  SvgAnimationStats stats;
  io::write_text_atomically(path, a.finish(fps, &stats));
  return stats;
}

}  // namespace wisp::render
