// Checked access to a YAML document: every value is read through a Field that knows
// its key path and its place in the file, so every problem becomes a ScenarioError
// "<file>:<line>:<column>: <key path>: <problem>". Private to the run library.
#pragma once

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace fireswarm::run::internal {

/// A closed, open or half-open interval of allowed values, for messages like
/// "must be in (0, 86400], got 0". Infinite ends print as "> min" / ">= min".
struct Range {
  double min;
  double max;
  bool min_open = false;
  bool max_open = false;
  bool Contains(double value) const;
  std::string Describe() const;  ///< "in [0, 1]", "> 0", ">= 0"
};

/// The YAML document of `text`; throws ScenarioError "<source>:<line>:<column>:
/// malformed YAML: ..." when it is not YAML.
YAML::Node LoadYaml(std::string_view text, const std::string& source_name);

/// The text of the configuration file at `path` (`what`: "scenario file", "sweep
/// file"). Throws ScenarioError "<path>: is a directory, not a <what>" or
/// "<path>: cannot open|read the <what>".
std::string ReadConfigFile(const std::filesystem::path& path, const std::string& what);

/// `<source>:<line>:<column>: ` for `mark`, or `<source>: ` when the mark is null.
std::string Where(const std::string& source, const YAML::Mark& mark);

/// The valid name nearest to `name` by edit distance (the first on ties).
std::string_view Nearest(std::string_view name, std::span<const std::string_view> valid);

/// `a|b|c`.
std::string JoinNames(std::span<const std::string_view> names);

/// One YAML node, its key path (`fleet.count`, `fires[2].lat`) and the file it is in.
class Field {
 public:
  Field(const std::string& source, YAML::Node node, std::string path)
      : source_(&source), node_(std::move(node)), path_(std::move(path)) {}

  const std::string& path() const { return path_; }
  const YAML::Node& node() const { return node_; }
  const std::string& source() const { return *source_; }

  /// Throws ScenarioError "<file>:<line>:<col>: <path>: <problem>".
  [[noreturn]] void Fail(const std::string& problem) const;

  bool IsMap() const { return node_.IsMap(); }
  bool IsSequence() const { return node_.IsSequence(); }
  bool IsScalar() const { return node_.IsScalar(); }

  /// A finite number (an unquoted YAML int or float).
  double Number() const;
  /// Number() within `range`.
  double Number(const Range& range) const;
  /// An integer (no fraction, no exponent) in [min, max].
  std::int64_t Integer(std::int64_t min, std::int64_t max) const;
  /// An unsigned 64-bit integer (a seed).
  std::uint64_t Unsigned64() const;
  /// `true` or `false`.
  bool Bool() const;
  /// Any non-empty scalar.
  std::string Text() const;
  /// A scalar that is one of `names`; its index in `names`.
  std::size_t OneOf(std::span<const std::string_view> names) const;

  /// The elements of a sequence, paths `<path>[i]`. Fails when not a sequence.
  std::vector<Field> Elements() const;

  /// Precondition: a key of a mapping (sequence element) this Field is a child of.
  Field Child(YAML::Node node, std::string path) const { return {*source_, std::move(node), path}; }

 private:
  std::string Describe() const;  ///< what the value is, for "got ..." messages
  std::string Scalar() const;    ///< the scalar; fails on a mapping, a list or nothing
  bool IsQuoted() const;         ///< a quoted scalar: "5" is a string, not a number

  const std::string* source_;
  YAML::Node node_;
  std::string path_;
};

/// A YAML mapping whose keys must all be among `keys`: an unknown key fails naming
/// the nearest valid one, a repeated key fails, a key with no value fails.
class Mapping {
 public:
  Mapping(const Field& field, std::initializer_list<std::string_view> keys);

  const Field& field() const { return field_; }
  std::optional<Field> Find(std::string_view key) const;
  /// Fails "<path>.<key>: missing (required)" at the mapping's position.
  Field Required(std::string_view key) const;
  bool Has(std::string_view key) const { return Find(key).has_value(); }

  /// Optional keys with defaults.
  double Number(std::string_view key, double fallback, const Range& range) const;
  int Integer(std::string_view key, int fallback, int min, int max) const;

 private:
  Field field_;
  std::vector<std::pair<std::string, YAML::Node>> entries_;
};

}  // namespace fireswarm::run::internal
