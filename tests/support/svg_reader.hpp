#pragma once
// Reads back what io/svg_plot drew: checks the document is well formed (every tag closed in order, quoted
// attributes), lists its elements with the panel each lies in, and turns pixel positions back into values
// through a panel's own tick labels (what a reader of the figure does).
#include <cctype>
#include <cmath>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace imucal::testing {

struct SvgElement {
  std::string name;
  std::map<std::string, std::string> attrs;
  std::string text;
  std::string panel;  // id of the enclosing <g class="panel">, "" outside any
  std::string attr(const std::string& k) const {
    const auto it = attrs.find(k);
    return it == attrs.end() ? "" : it->second;
  }
};

struct SvgDocument {
  std::string error;  // empty when well formed
  std::vector<SvgElement> elements;

  std::vector<const SvgElement*> find(const std::string& name, const std::string& cls, const std::string& panel) const {
    std::vector<const SvgElement*> out;
    for (const auto& e : elements)
      if (e.name == name && (cls.empty() || e.attr("class") == cls || e.attr("class").rfind(cls + " ", 0) == 0) &&
          (panel.empty() || e.panel == panel))
        out.push_back(&e);
    return out;
  }
};

// nullopt for an '&' that starts no known entity.
inline std::optional<std::string> unescapeXml(const std::string& s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] != '&') {
      out += s[i];
      continue;
    }
    const std::size_t end = s.find(';', i);
    const std::string entity = end == std::string::npos ? "" : s.substr(i + 1, end - i - 1);
    if (entity == "lt") out += '<';
    else if (entity == "gt") out += '>';
    else if (entity == "amp") out += '&';
    else if (entity == "quot") out += '"';
    else return std::nullopt;
    i = end;
  }
  return out;
}

inline SvgDocument readSvg(const std::string& s) {
  SvgDocument doc;
  std::vector<std::size_t> open;  // indices into elements
  const auto fail = [&](const std::string& why, std::size_t at) {
    doc.error = why + " at offset " + std::to_string(at);
    return doc;
  };
  std::size_t i = 0;
  while (i < s.size()) {
    if (s[i] != '<') {
      const std::size_t next = s.find('<', i);
      const std::string text = s.substr(i, next == std::string::npos ? std::string::npos : next - i);
      if (text.find('>') != std::string::npos) return fail("stray '>'", i);
      const auto plain = unescapeXml(text);
      if (!plain) return fail("bad entity", i);
      if (!open.empty()) doc.elements[open.back()].text += *plain;
      else if (text.find_first_not_of(" \n\t") != std::string::npos) return fail("text outside the root", i);
      if (next == std::string::npos) break;
      i = next;
      continue;
    }
    if (s.compare(i, 2, "</") == 0) {
      const std::size_t end = s.find('>', i);
      if (end == std::string::npos) return fail("unterminated closing tag", i);
      const std::string name = s.substr(i + 2, end - i - 2);
      if (open.empty() || doc.elements[open.back()].name != name) return fail("</" + name + "> closes nothing open", i);
      open.pop_back();
      i = end + 1;
      continue;
    }
    SvgElement e;
    std::size_t j = i + 1;
    while (j < s.size() && (std::isalnum(static_cast<unsigned char>(s[j])) || s[j] == '-' || s[j] == ':')) e.name += s[j++];
    if (e.name.empty()) return fail("tag without a name", i);
    bool self_closing = false;
    while (true) {
      while (j < s.size() && std::isspace(static_cast<unsigned char>(s[j]))) ++j;
      if (j >= s.size()) return fail("unterminated tag", i);
      if (s[j] == '>') {
        ++j;
        break;
      }
      if (s.compare(j, 2, "/>") == 0) {
        self_closing = true;
        j += 2;
        break;
      }
      std::string key;
      while (j < s.size() && s[j] != '=' && !std::isspace(static_cast<unsigned char>(s[j]))) key += s[j++];
      if (j + 1 >= s.size() || s[j] != '=' || s[j + 1] != '"') return fail("attribute " + key + " not quoted", j);
      const std::size_t close = s.find('"', j + 2);
      if (close == std::string::npos) return fail("unterminated attribute", j);
      const std::string raw = s.substr(j + 2, close - j - 2);
      if (raw.find('<') != std::string::npos) return fail("'<' in attribute " + key, j);
      if (e.attrs.count(key) != 0) return fail("attribute " + key + " twice", j);
      const auto value = unescapeXml(raw);
      if (!value) return fail("bad entity in attribute " + key, j);
      e.attrs[key] = *value;
      j = close + 1;
    }
    if (open.empty() && !doc.elements.empty()) return fail("second root element", i);
    e.panel = open.empty() ? "" : doc.elements[open.back()].panel;
    if (e.name == "g" && e.attr("class") == "panel") e.panel = e.attr("id").substr(std::string("panel-").size());
    doc.elements.push_back(e);
    if (!self_closing) open.push_back(doc.elements.size() - 1);
    i = j;
  }
  if (!open.empty()) doc.error = "<" + doc.elements[open.back()].name + "> never closed";
  if (doc.elements.empty()) doc.error = "no elements";
  return doc;
}

// Pixel -> value on one axis of a panel, from its first and last tick labels ("xtick" or "ytick").
struct SvgAxis {
  double p0 = 0, v0 = 0, p1 = 1, v1 = 1;
  bool log = false;
  // The values between the outer ticks: the scale tolerances of a read-back go by.
  double range() const { return std::abs(v1 - v0); }
  double value(double p) const {
    const double t = (p - p0) / (p1 - p0);
    return log ? std::pow(10.0, std::log10(v0) + t * (std::log10(v1) - std::log10(v0))) : v0 + t * (v1 - v0);
  }
};

inline SvgAxis svgAxis(const SvgDocument& doc, const std::string& panel, const std::string& tick_class, bool log = false) {
  const auto ticks = doc.find("text", tick_class, panel);
  SvgAxis a;
  a.log = log;
  if (ticks.size() < 2) return a;
  a.p0 = std::stod(ticks.front()->attr("data-at"));
  a.v0 = std::stod(ticks.front()->text);
  a.p1 = std::stod(ticks.back()->attr("data-at"));
  a.v1 = std::stod(ticks.back()->text);
  return a;
}

// "x,y x,y ..." of a polyline or polygon.
inline std::vector<std::pair<double, double>> svgPoints(const SvgElement& e) {
  std::vector<std::pair<double, double>> out;
  std::istringstream in(e.attr("points"));
  std::string pair;
  while (in >> pair) {
    const std::size_t comma = pair.find(',');
    out.emplace_back(std::stod(pair.substr(0, comma)), std::stod(pair.substr(comma + 1)));
  }
  return out;
}

}  // namespace imucal::testing
