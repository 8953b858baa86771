// A small strict XML reader for the run's XML outputs (SVG map, JUnit): enough to
// prove a document well-formed (one root, tags balanced and nested, attributes
// quoted and unique, every & an entity, no < in attribute values) and to look up
// elements by name and attribute with entities decoded. Not a general XML parser:
// no DTD, no CDATA, no namespaces beyond taking "a:b" as a name.
#pragma once

#include <cctype>
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace fireswarm::run::test {

struct XmlElement {
  std::string name;
  std::map<std::string, std::string> attributes;  ///< values decoded
  std::string text;                               ///< direct text content, decoded
  std::optional<std::size_t> parent;              ///< index into XmlDocument::elements

  std::string Attribute(const std::string& key) const {
    const auto it = attributes.find(key);
    return it == attributes.end() ? std::string() : it->second;
  }
};

struct XmlDocument {
  std::vector<XmlElement> elements;  ///< in document order; elements[0] is the root
  std::string error;                 ///< empty when well-formed

  /// Elements named `name` (any, when empty) whose ancestors include one with id
  /// `ancestor_id` (any, when empty).
  std::vector<const XmlElement*> Find(const std::string& name,
                                      const std::string& ancestor_id = "") const {
    std::vector<const XmlElement*> found;
    for (const XmlElement& element : elements) {
      if (!name.empty() && element.name != name) continue;
      if (!ancestor_id.empty() && !HasAncestor(element, ancestor_id)) continue;
      found.push_back(&element);
    }
    return found;
  }

  const XmlElement* ById(const std::string& id) const {
    for (const XmlElement& element : elements) {
      if (element.Attribute("id") == id) return &element;
    }
    return nullptr;
  }

 private:
  bool HasAncestor(const XmlElement& element, const std::string& id) const {
    for (auto parent = element.parent; parent; parent = elements[*parent].parent) {
      if (elements[*parent].Attribute("id") == id) return true;
    }
    return false;
  }
};

namespace detail {

inline bool IsNameChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '-' || c == '_' || c == ':' ||
         c == '.';
}

// Decodes the entities of `raw`; nullopt on a bare '&' or an unknown entity.
inline std::optional<std::string> Decode(std::string_view raw) {
  std::string out;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    if (raw[i] != '&') {
      out += raw[i];
      continue;
    }
    const std::size_t end = raw.find(';', i);
    if (end == std::string_view::npos) return std::nullopt;
    const std::string_view entity = raw.substr(i + 1, end - i - 1);
    if (entity == "amp")
      out += '&';
    else if (entity == "lt")
      out += '<';
    else if (entity == "gt")
      out += '>';
    else if (entity == "quot")
      out += '"';
    else if (entity == "apos")
      out += '\'';
    else if (entity.size() > 1 && entity[0] == '#' &&
             entity.find_first_not_of("0123456789", 1) == std::string_view::npos) {
      const int code = std::stoi(std::string(entity.substr(1)));
      if (code >= 128) return std::nullopt;  // ASCII is all the outputs reference
      out += static_cast<char>(code);
    } else {
      return std::nullopt;
    }
    i = end;
  }
  return out;
}

}  // namespace detail

inline XmlDocument ParseXml(std::string_view xml) {
  XmlDocument doc;
  std::vector<std::size_t> open;
  bool root_closed = false;
  std::size_t i = 0;
  const auto fail = [&](const std::string& what) {
    doc.error = what + " at offset " + std::to_string(i);
    return doc;
  };
  if (xml.starts_with("<?xml")) {
    i = xml.find("?>");
    if (i == std::string_view::npos) return fail("unterminated XML declaration");
    i += 2;
  }
  while (i < xml.size()) {
    if (xml[i] != '<') {
      const std::size_t end = std::min(xml.find('<', i), xml.size());
      const std::string_view raw = xml.substr(i, end - i);
      const auto text = detail::Decode(raw);
      if (!text) return fail("bad entity in text");
      if (raw.find('>') != std::string_view::npos) return fail("'>' in text");
      if (open.empty()) {
        if (text->find_first_not_of(" \t\r\n") != std::string::npos) {
          return fail("text outside the root");
        }
      } else {
        doc.elements[open.back()].text += *text;
      }
      i = end;
      continue;
    }
    if (xml.substr(i).starts_with("<!--")) {
      const std::size_t end = xml.find("-->", i);
      if (end == std::string_view::npos) return fail("unterminated comment");
      i = end + 3;
      continue;
    }
    if (xml.substr(i).starts_with("</")) {
      std::size_t j = i + 2;
      while (j < xml.size() && detail::IsNameChar(xml[j])) ++j;
      const std::string name(xml.substr(i + 2, j - i - 2));
      while (j < xml.size() && std::isspace(static_cast<unsigned char>(xml[j])) != 0) ++j;
      if (j >= xml.size() || xml[j] != '>') return fail("bad end tag");
      if (open.empty() || doc.elements[open.back()].name != name) {
        return fail("end tag </" + name + "> does not match");
      }
      open.pop_back();
      if (open.empty()) root_closed = true;
      i = j + 1;
      continue;
    }
    // A start tag.
    if (root_closed) return fail("a second root element");
    std::size_t j = i + 1;
    while (j < xml.size() && detail::IsNameChar(xml[j])) ++j;
    XmlElement element;
    element.name = std::string(xml.substr(i + 1, j - i - 1));
    if (element.name.empty()) return fail("empty tag name");
    if (!open.empty()) element.parent = open.back();
    bool self_closing = false;
    while (true) {
      while (j < xml.size() && std::isspace(static_cast<unsigned char>(xml[j])) != 0) ++j;
      if (j >= xml.size()) return fail("unterminated tag");
      if (xml[j] == '>') break;
      if (xml.substr(j).starts_with("/>")) {
        self_closing = true;
        ++j;
        break;
      }
      std::size_t k = j;
      while (k < xml.size() && detail::IsNameChar(xml[k])) ++k;
      const std::string key(xml.substr(j, k - j));
      if (key.empty() || k + 1 >= xml.size() || xml[k] != '=' || xml[k + 1] != '"') {
        i = k;
        return fail("attribute not key=\"value\"");
      }
      const std::size_t close = xml.find('"', k + 2);
      if (close == std::string_view::npos) return fail("unterminated attribute");
      const std::string_view raw = xml.substr(k + 2, close - k - 2);
      const auto value = detail::Decode(raw);
      if (!value || raw.find('<') != std::string_view::npos) {
        i = k;
        return fail("bad attribute value of " + key);
      }
      if (!element.attributes.emplace(key, *value).second) return fail("duplicate " + key);
      j = close + 1;
      if (j < xml.size() && std::isspace(static_cast<unsigned char>(xml[j])) == 0 &&
          xml[j] != '>' && xml[j] != '/') {
        return fail("no space between attributes");
      }
    }
    doc.elements.push_back(std::move(element));
    if (self_closing) {
      if (open.empty()) root_closed = true;
    } else {
      open.push_back(doc.elements.size() - 1);
    }
    i = j + 1;
  }
  if (!open.empty()) return fail("unclosed <" + doc.elements[open.back()].name + ">");
  if (doc.elements.empty()) return fail("no root element");
  return doc;
}

}  // namespace fireswarm::run::test
