// Text and numbers as the run's XML outputs (the SVG map, the JUnit file) write
// them: escaped, and formatted the same on every machine (std::to_chars, no locale).
// Private to the run library.
#pragma once

#include <array>
#include <charconv>
#include <string>
#include <string_view>

namespace fireswarm::run::internal {

/// Where escaped text goes: an attribute value must keep its tabs and newlines as
/// character references (a parser normalises literal ones to spaces); element text
/// keeps them as they are, for people reading the file.
enum class XmlPlace { kAttribute, kText };

/// `text` safe inside a double-quoted XML attribute value (the default) or element
/// text: & < > " ' as entities, tab and newline as said for XmlPlace, carriage
/// return as a character reference, and the other control characters, which XML
/// 1.0 cannot hold at all, as '?'. Other bytes (UTF-8) pass unchanged.
inline std::string XmlEscape(std::string_view text, XmlPlace place = XmlPlace::kAttribute) {
  const bool attribute = place == XmlPlace::kAttribute;
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      case '\t':
        out += attribute ? "&#9;" : "\t";
        break;
      case '\n':
        out += attribute ? "&#10;" : "\n";
        break;
      case '\r':
        out += "&#13;";
        break;
      default: {
        const auto byte = static_cast<unsigned char>(c);
        constexpr unsigned char kFirstPrintable = 0x20;
        constexpr unsigned char kDelete = 0x7f;
        out += (byte < kFirstPrintable || byte == kDelete) ? '?' : c;
      }
    }
  }
  return out;
}

/// `value` with exactly `decimals` digits after the point ("12.5"); "-0.0" comes out
/// as "0.0" so that a value rounding to zero reads the same from either side.
inline std::string FixedNumber(double value, int decimals) {
  std::array<char, 64> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value,
                                    std::chars_format::fixed, decimals);
  if (result.ec != std::errc{}) return "nan";  // only a huge value overflows 64 chars
  std::string text(buffer.data(), result.ptr);
  if (text.starts_with('-') && text.find_first_not_of("-0.") == std::string::npos) {
    text.erase(0, 1);
  }
  return text;
}

/// `value` in at most `significant` significant digits, no trailing zeros
/// ("0.873457", "12.34", "2", "1e+06").
inline std::string ShortNumber(double value, int significant = 6) {
  std::array<char, 64> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value,
                                    std::chars_format::general, significant);
  return std::string(buffer.data(), result.ptr);
}

}  // namespace fireswarm::run::internal
