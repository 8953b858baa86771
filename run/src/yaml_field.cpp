#include "yaml_field.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <system_error>

#include "fireswarm/run/scenario.hpp"

namespace fireswarm::run::internal {
namespace {

// yaml-cpp tags a quoted scalar "!" and a plain one "?": "5" is a string, 5 a number.
constexpr std::string_view kQuotedScalarTag = "!";

std::string FormatNumber(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

// Full-string parse with std::from_chars; a leading '+' is allowed as YAML allows it.
// (An out-parameter, not std::optional: GCC 12 reports a false -Wmaybe-uninitialized
// on the optional's value.)
template <typename T>
bool ParseWhole(std::string_view text, T& value) {
  if (text.size() > 1 && text.front() == '+') text.remove_prefix(1);
  const char* end = text.data() + text.size();
  const auto [ptr, error] = std::from_chars(text.data(), end, value);
  return error == std::errc() && ptr == end;
}

std::size_t EditDistance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> previous(b.size() + 1);
  std::vector<std::size_t> current(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) previous[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    current[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t substitution = previous[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      current[j] = std::min({previous[j] + 1, current[j - 1] + 1, substitution});
    }
    std::swap(previous, current);
  }
  return previous[b.size()];
}

std::string ChildPath(const std::string& parent, std::string_view key) {
  return parent.empty() ? std::string(key) : parent + "." + std::string(key);
}

}  // namespace

bool Range::Contains(double value) const {
  const bool above = min_open ? value > min : value >= min;
  const bool below = max_open ? value < max : value <= max;
  return above && below;
}

std::string Range::Describe() const {
  if (std::isinf(max)) return (min_open ? "> " : ">= ") + FormatNumber(min);
  return std::string("in ") + (min_open ? "(" : "[") + FormatNumber(min) + ", " +
         FormatNumber(max) + (max_open ? ")" : "]");
}

YAML::Node LoadYaml(std::string_view text, const std::string& source_name) {
  try {
    return YAML::Load(std::string(text));
  } catch (const YAML::Exception& e) {
    throw ScenarioError(Where(source_name, e.mark) + "malformed YAML: " + e.msg);
  }
}

std::string ReadConfigFile(const std::filesystem::path& path, const std::string& what) {
  std::error_code error;  // the throwing overload throws for a name too long
  if (std::filesystem::is_directory(path, error)) {
    throw ScenarioError(path.string() + ": is a directory, not a " + what);
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw ScenarioError(path.string() + ": cannot open the " + what +
                        (error ? " (" + error.message() + ")" : ""));
  }
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw ScenarioError(path.string() + ": cannot read the " + what);
  return text.str();
}

std::string Where(const std::string& source, const YAML::Mark& mark) {
  if (mark.is_null()) return source + ": ";
  return source + ":" + std::to_string(mark.line + 1) + ":" + std::to_string(mark.column + 1) +
         ": ";
}

std::string_view Nearest(std::string_view name, std::span<const std::string_view> valid) {
  std::string_view best;
  std::size_t best_distance = std::numeric_limits<std::size_t>::max();
  for (const std::string_view candidate : valid) {
    const std::size_t distance = EditDistance(name, candidate);
    if (distance < best_distance) {
      best_distance = distance;
      best = candidate;
    }
  }
  return best;
}

std::string JoinNames(std::span<const std::string_view> names) {
  std::string out;
  for (const std::string_view name : names) {
    if (!out.empty()) out += '|';
    out += name;
  }
  return out;
}

void Field::Fail(const std::string& problem) const {
  throw ScenarioError(Where(*source_, node_.Mark()) + path_ + ": " + problem);
}

std::string Field::Describe() const {
  switch (node_.Type()) {
    case YAML::NodeType::Map:
      return "a mapping";
    case YAML::NodeType::Sequence:
      return "a list";
    case YAML::NodeType::Scalar:
      return IsQuoted() ? "the string \"" + node_.Scalar() + "\"" : node_.Scalar();
    default:
      return "nothing";
  }
}

bool Field::IsQuoted() const {
  return node_.Tag() == kQuotedScalarTag;
}

std::string Field::Scalar() const {
  if (!node_.IsScalar()) Fail("must be a single value, got " + Describe());
  return node_.Scalar();
}

double Field::Number() const {
  const std::string text = Scalar();
  double value = 0.0;
  if (IsQuoted() || !ParseWhole(text, value) || !std::isfinite(value)) {
    Fail("must be a finite number, got " + Describe());
  }
  return value;
}

double Field::Number(const Range& range) const {
  const double value = Number();
  if (!range.Contains(value)) Fail("must be " + range.Describe() + ", got " + Describe());
  return value;
}

std::int64_t Field::Integer(std::int64_t min, std::int64_t max) const {
  const std::string text = Scalar();
  const std::string interval = "[" + std::to_string(min) + ", " + std::to_string(max) + "]";
  std::int64_t value = 0;
  if (IsQuoted() || !ParseWhole(text, value)) {
    Fail("must be an integer in " + interval + ", got " + Describe());
  }
  if (value < min || value > max) Fail("must be in " + interval + ", got " + Describe());
  return value;
}

std::uint64_t Field::Unsigned64() const {
  const std::string text = Scalar();
  std::uint64_t value = 0;
  if (IsQuoted() || !ParseWhole(text, value)) {
    Fail("must be an integer in [0, " + std::to_string(std::numeric_limits<std::uint64_t>::max()) +
         "], got " + Describe());
  }
  return value;
}

bool Field::Bool() const {
  const std::string text = Scalar();
  if (!IsQuoted()) {
    if (text == "true" || text == "True" || text == "TRUE") return true;
    if (text == "false" || text == "False" || text == "FALSE") return false;
  }
  Fail("must be true or false, got " + Describe());
}

std::string Field::Text() const {
  std::string text = Scalar();
  if (text.empty()) Fail("must not be empty");
  return text;
}

std::size_t Field::OneOf(std::span<const std::string_view> names) const {
  const std::string text = Scalar();
  const auto found = std::find(names.begin(), names.end(), text);
  if (found == names.end()) {
    // A suggestion only for a likely typo: a far-fetched one would confuse.
    const std::string_view nearest = Nearest(text, names);
    const bool close = EditDistance(text, nearest) <= std::max<std::size_t>(2, text.size() / 3);
    Fail("must be one of " + JoinNames(names) + ", got " + Describe() +
         (close ? " (did you mean '" + std::string(nearest) + "'?)" : std::string()));
  }
  return static_cast<std::size_t>(found - names.begin());
}

std::vector<Field> Field::Elements() const {
  if (!node_.IsSequence()) Fail("must be a list, got " + Describe());
  std::vector<Field> elements;
  elements.reserve(node_.size());
  std::size_t index = 0;
  for (const YAML::Node& element : node_) {
    elements.push_back(Child(element, path_ + "[" + std::to_string(index) + "]"));
    if (element.IsNull()) elements.back().Fail("has no value");
    ++index;
  }
  return elements;
}

Mapping::Mapping(const Field& field, std::initializer_list<std::string_view> keys) : field_(field) {
  const std::vector<std::string_view> valid(keys);
  if (!field.IsMap()) {
    field.Fail("must be a mapping with keys " + JoinNames(valid) + ", got " +
               (field.IsSequence() ? std::string("a list") : "'" + field.node().Scalar() + "'"));
  }
  for (const auto& entry : field.node()) {
    // Copies: the iterator's pair is a temporary and Node is a cheap handle.
    const YAML::Node key_node = entry.first;
    const YAML::Node value_node = entry.second;
    const std::string key = key_node.IsScalar() ? key_node.Scalar() : std::string("?");
    const Field key_field = field.Child(key_node, ChildPath(field.path(), key));
    if (!key_node.IsScalar()) key_field.Fail("a key must be a plain name");
    if (std::find(valid.begin(), valid.end(), key) == valid.end()) {
      key_field.Fail("unknown key; did you mean '" + std::string(Nearest(key, valid)) +
                     "'? (valid keys: " + JoinNames(valid) + ")");
    }
    for (const auto& [seen, seen_node] : entries_) {
      if (seen == key) key_field.Fail("repeated key");
    }
    if (value_node.IsNull()) key_field.Fail("has no value");
    entries_.emplace_back(key, value_node);
  }
}

std::optional<Field> Mapping::Find(std::string_view key) const {
  for (const auto& [name, node] : entries_) {
    if (name == key) return field_.Child(node, ChildPath(field_.path(), key));
  }
  return std::nullopt;
}

Field Mapping::Required(std::string_view key) const {
  std::optional<Field> found = Find(key);
  if (!found) {
    throw ScenarioError(Where(field_.source(), field_.node().Mark()) +
                        ChildPath(field_.path(), key) + ": missing (required)");
  }
  return *found;
}

double Mapping::Number(std::string_view key, double fallback, const Range& range) const {
  const std::optional<Field> found = Find(key);
  return found ? found->Number(range) : fallback;
}

int Mapping::Integer(std::string_view key, int fallback, int min, int max) const {
  const std::optional<Field> found = Find(key);
  return found ? static_cast<int>(found->Integer(min, max)) : fallback;
}

}  // namespace fireswarm::run::internal
