// POST /api/command bodies -> OperatorCommand.
#include "fireswarm/server/web_command.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string_view>

namespace fireswarm::server {

namespace {

using Kind = OperatorCommand::Kind;

/// The largest loiter radius an operator may ask for, metres.
constexpr double kMaxRadiusM = 10'000.0;

enum class Need { kNo, kOptional, kRequired };

struct KindSpec {
  std::string_view name;
  Kind kind;
  Need vehicle;
  Need point;  // lat and lon together
  Need radius;
};

constexpr std::array<KindSpec, 11> kKinds = {{
    {"hold", Kind::kHold, Need::kRequired, Need::kNo, Need::kNo},
    {"resume", Kind::kResume, Need::kRequired, Need::kNo, Need::kNo},
    {"return", Kind::kReturnVehicle, Need::kRequired, Need::kNo, Need::kNo},
    {"land", Kind::kLand, Need::kRequired, Need::kNo, Need::kNo},
    {"retask", Kind::kRetaskVehicle, Need::kRequired, Need::kRequired, Need::kOptional},
    {"investigate", Kind::kInvestigatePoint, Need::kOptional, Need::kRequired, Need::kOptional},
    {"start", Kind::kStart, Need::kNo, Need::kNo, Need::kNo},
    {"hold_all", Kind::kHoldAll, Need::kNo, Need::kNo, Need::kNo},
    {"resume_all", Kind::kResumeAll, Need::kNo, Need::kNo, Need::kNo},
    {"return_all", Kind::kReturnAll, Need::kNo, Need::kNo, Need::kNo},
    {"abort", Kind::kAbort, Need::kNo, Need::kNo, Need::kNo},
}};

// Reads one field by its spec; false (with the problem in `why`) when it is
// missing but required, present but not taken, or out of range.
class Reader {
 public:
  Reader(const nlohmann::json& body, const KindSpec& spec, std::string* why)
      : body_(body), spec_(spec), why_(why) {}

  bool Present(const char* key, Need need) {
    const bool present = body_.contains(key);
    if (need == Need::kRequired && !present) return Fail(std::string(key) + ": required");
    if (need == Need::kNo && present) {
      return Fail(std::string(key) + ": not taken by '" + std::string(spec_.name) + "'");
    }
    return true;
  }

  bool Number(const char* key, double low, double high, double* out) {
    const nlohmann::json& value = body_.at(key);
    if (!value.is_number() || !(value.get<double>() >= low) || !(value.get<double>() <= high)) {
      return Fail(std::string(key) + ": must be a number in [" + Text(low) + ", " + Text(high) +
                  "]");
    }
    *out = value.get<double>();
    return true;
  }

  bool Vehicle(std::uint8_t* out) {
    const nlohmann::json& value = body_.at("vehicle");
    if (!value.is_number_integer() || value.get<std::int64_t>() < 1 ||
        value.get<std::int64_t>() > 254 ||
        (value.is_number_unsigned() && value.get<std::uint64_t>() > 254)) {
      return Fail("vehicle: must be an integer 1..254");
    }
    *out = static_cast<std::uint8_t>(value.get<std::int64_t>());
    return true;
  }

  bool Fail(std::string problem) {
    if (why_ != nullptr) *why_ = std::move(problem);
    return false;
  }

 private:
  static std::string Text(double value) {
    std::string text = std::to_string(value);
    text.erase(text.find_last_not_of('0') + 1);
    if (!text.empty() && text.back() == '.') text.pop_back();
    return text;
  }

  const nlohmann::json& body_;
  const KindSpec& spec_;
  std::string* why_;
};

bool Fail(std::string* why, std::string problem) {
  if (why != nullptr) *why = std::move(problem);
  return false;
}

const KindSpec* FindKind(const nlohmann::json& body, std::string* why) {
  const auto kind = body.find("kind");
  if (kind == body.end()) return Fail(why, "kind: required"), nullptr;
  if (!kind->is_string()) return Fail(why, "kind: must be a string"), nullptr;
  const std::string& name = kind->get_ref<const std::string&>();
  for (const KindSpec& spec : kKinds) {
    if (spec.name == name) return &spec;
  }
  // Quoted as given, cut short: an error must not echo a whole hostile body.
  constexpr std::size_t kEchoBytes = 40;
  return Fail(why, "kind: unknown '" + name.substr(0, kEchoBytes) + "'"), nullptr;
}

bool KnownKeys(const nlohmann::json& body, std::string* why) {
  static constexpr std::array<std::string_view, 6> kKeys = {"kind", "vehicle",  "lat",
                                                            "lon",  "radius_m", "reason"};
  for (const auto& [key, value] : body.items()) {
    if (std::find(kKeys.begin(), kKeys.end(), key) == kKeys.end()) {
      constexpr std::size_t kEchoBytes = 40;
      return Fail(why, key.substr(0, kEchoBytes) + ": unknown field");
    }
  }
  return true;
}

}  // namespace

std::optional<OperatorCommand> ParseWebCommand(const nlohmann::json& body, std::string* why) {
  if (!body.is_object()) return Fail(why, "body: must be a JSON object"), std::nullopt;
  if (!KnownKeys(body, why)) return std::nullopt;
  const KindSpec* spec = FindKind(body, why);
  if (spec == nullptr) return std::nullopt;
  Reader read(body, *spec, why);
  OperatorCommand command;
  command.kind = spec->kind;
  if (!read.Present("vehicle", spec->vehicle)) return std::nullopt;
  if (body.contains("vehicle") && !read.Vehicle(&command.vehicle)) return std::nullopt;
  if (!read.Present("lat", spec->point) || !read.Present("lon", spec->point)) return std::nullopt;
  if (body.contains("lat") != body.contains("lon")) {
    return read.Fail(body.contains("lat") ? "lon: required with lat" : "lat: required with lon"),
           std::nullopt;
  }
  if (body.contains("lat") && (!read.Number("lat", -90.0, 90.0, &command.point.lat_deg) ||
                               !read.Number("lon", -180.0, 180.0, &command.point.lon_deg))) {
    return std::nullopt;
  }
  if (!read.Present("radius_m", spec->radius)) return std::nullopt;
  if (body.contains("radius_m") && !read.Number("radius_m", 0.0, kMaxRadiusM, &command.radius_m)) {
    return std::nullopt;
  }
  if (const auto reason = body.find("reason"); reason != body.end()) {
    if (!reason->is_string() || reason->get_ref<const std::string&>().size() > kMaxReasonBytes) {
      return read.Fail("reason: must be a string of at most " + std::to_string(kMaxReasonBytes) +
                       " bytes"),
             std::nullopt;
    }
    command.reason = reason->get<std::string>();
  }
  return command;
}

}  // namespace fireswarm::server
