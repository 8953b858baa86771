// ParamStore: the values, their checks, and their JSON file (seed 3.3's EEPROM).
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "fireswarm/agents/params.hpp"
#include "fireswarm/common/atomic_file.hpp"

namespace fireswarm::agents {
namespace {

using Json = nlohmann::json;
using OrderedJson = nlohmann::ordered_json;

constexpr std::string_view kFormat = "fireswarm-params";
constexpr int kVersion = 1;
constexpr int kJsonIndent = 2;

std::size_t IndexOf(const ParamSpec& spec) {
  return static_cast<std::size_t>(&spec - ParamTable().data());
}

// Shortest decimal that reads back as the same float: the file shows 0.1, not
// 0.100000001490116, and loading it gives the bits that were written.
std::string FloatText(float value) {
  std::array<char, 32> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  return {buffer.data(), result.ptr};
}

double FloatForJson(float value) {
  const std::string text = FloatText(value);
  double out = 0.0;
  std::from_chars(text.data(), text.data() + text.size(), out);
  return out;
}

// `value` as the nearest float; nullopt beyond float's range (a cast would be UB).
std::optional<float> AsFloat(double value) {
  if (!(std::abs(value) <= static_cast<double>(std::numeric_limits<float>::max()))) {
    return std::nullopt;
  }
  return static_cast<float>(value);
}

bool InRange(const ParamSpec& spec, float value) {
  return std::isfinite(value) && value >= spec.min && value <= spec.max;
}

[[noreturn]] void ThrowCorrupt(const std::filesystem::path& file, const std::string& key,
                               const std::string& problem) {
  throw std::runtime_error("parameter file " + file.string() + ": " +
                           (key.empty() ? "" : "key \"" + key + "\": ") + problem);
}

std::string ReadText(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in.is_open()) ThrowCorrupt(file, "", std::string("cannot open: ") + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) ThrowCorrupt(file, "", "cannot read");
  return text.str();
}

// Checks everything but the values; returns the vehicle the file was written for.
std::uint8_t CheckHeader(const std::filesystem::path& file, const Json& root,
                         std::uint8_t vehicle) {
  if (!root.is_object()) ThrowCorrupt(file, "", "not a JSON object");
  const auto field = [&root](const char* key) {
    return root.contains(key) ? root.at(key) : Json();
  };
  if (const Json format = field("format");
      !format.is_string() || format.get<std::string>() != kFormat) {
    ThrowCorrupt(file, "format", "must be \"" + std::string(kFormat) + "\", got " + format.dump());
  }
  if (const Json version = field("version");
      !version.is_number_integer() || version.get<std::int64_t>() != kVersion) {
    ThrowCorrupt(file, "version",
                 "must be " + std::to_string(kVersion) + ", got " + version.dump());
  }
  const Json id = field("vehicle");
  const auto max_vehicle = std::numeric_limits<std::uint8_t>::max();
  if (!id.is_number_integer() || id.get<std::int64_t>() < 0 ||
      id.get<std::int64_t>() > max_vehicle) {
    ThrowCorrupt(file, "vehicle", "must be a receiver ID, got " + id.dump());
  }
  const auto written_for = static_cast<std::uint8_t>(id.get<std::int64_t>());
  if (vehicle != 0 && written_for != vehicle) {
    ThrowCorrupt(file, "vehicle",
                 "the file is vehicle " + std::to_string(written_for) + "'s, this is vehicle " +
                     std::to_string(vehicle));
  }
  if (!field("params").is_object()) {
    ThrowCorrupt(file, "params", "must be an object of name: number");
  }
  return written_for;
}

}  // namespace

ParamStore::ParamStore(std::filesystem::path file, std::uint8_t vehicle)
    : file_(std::move(file)), vehicle_(vehicle) {
  for (const ParamSpec& spec : ParamTable()) values_.push_back(spec.default_value);
  if (!file_.empty()) Load();
}

float ParamStore::Get(ParamId id) const {
  return values_[IndexOf(SpecOf(id))];
}

radio::ParamValue ParamStore::Read(std::uint16_t id) const {
  radio::ParamValue reply;
  reply.param_id = id;
  const ParamSpec* spec = FindParam(id);
  if (spec == nullptr) {
    reply.status = radio::ParamStatus::kUnknownParam;
    return reply;
  }
  reply.value = values_[IndexOf(*spec)];
  reply.status = radio::ParamStatus::kOk;
  return reply;
}

radio::ParamValue ParamStore::Write(std::uint16_t id, float value) {
  radio::ParamValue reply = Read(id);
  if (reply.status != radio::ParamStatus::kOk) return reply;
  const ParamSpec& spec = *FindParam(id);
  if (spec.read_only) {
    reply.status = radio::ParamStatus::kReadOnly;
  } else if (!InRange(spec, value)) {
    reply.status = radio::ParamStatus::kOutOfRange;
  } else {
    values_[IndexOf(spec)] = value;
    reply.value = value;
    Persist();
  }
  return reply;
}

void ParamStore::Load() {
  std::error_code error;
  const bool exists = std::filesystem::exists(file_, error);
  if (error) ThrowCorrupt(file_, "", "cannot access: " + error.message());
  if (!exists) return;  // defaults; written at the first accepted write

  Json root;
  try {
    root = Json::parse(ReadText(file_));
  } catch (const Json::parse_error& e) {
    ThrowCorrupt(file_, "", std::string("not JSON: ") + e.what());
  }
  const std::uint8_t file_vehicle = CheckHeader(file_, root, vehicle_);

  // Checked in full before anything is kept: a bad file changes nothing.
  std::vector<float> values = values_;
  std::map<std::string, std::string> unknown;
  for (const auto& [name, value] : root["params"].items()) {
    const ParamSpec* spec = FindParam(std::string_view(name));
    if (spec == nullptr) {
      unknown[name] = value.dump();
      continue;
    }
    if (spec->read_only) continue;  // the firmware's, not the file's
    const std::string key = "params." + name;
    if (!value.is_number()) ThrowCorrupt(file_, key, "must be a number, got " + value.dump());
    const std::optional<float> number = AsFloat(value.get<double>());
    if (!number || !InRange(*spec, *number)) {
      ThrowCorrupt(file_, key,
                   value.dump() + " is outside [" + FloatText(spec->min) + ", " +
                       FloatText(spec->max) + "]");
    }
    values[IndexOf(*spec)] = *number;
  }
  values_ = std::move(values);
  unknown_ = std::move(unknown);
  vehicle_ = file_vehicle;
}

void ParamStore::Persist() {
  if (file_.empty()) return;
  // Write() answers radio callbacks: nothing may escape, not even bad_alloc.
  try {
    OrderedJson params = OrderedJson::object();
    for (const ParamSpec& spec : ParamTable()) {
      if (!spec.read_only) params[std::string(spec.name)] = FloatForJson(values_[IndexOf(spec)]);
    }
    for (const auto& [name, text] : unknown_) params[name] = OrderedJson::parse(text);
    OrderedJson root = OrderedJson::object();
    root["format"] = std::string(kFormat);
    root["version"] = kVersion;
    root["vehicle"] = vehicle_;
    root["params"] = std::move(params);
    common::WriteFileAtomically(file_, root.dump(kJsonIndent) + "\n");
  } catch (const std::runtime_error& e) {
    ++persist_errors_;
    last_persist_error_ = e.what();  // names the file and the step that failed
  } catch (const std::exception& e) {
    ++persist_errors_;
    last_persist_error_ = file_.string() + ": " + e.what();
  }
}

}  // namespace fireswarm::agents
