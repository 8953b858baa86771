// POST /api/command bodies -> OperatorCommand.
#include "fireswarm/server/web_command.hpp"

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <cstdint>
#include <span>
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
  static constexpr std::array<std::string_view, 7> kKeys = {"kind",     "vehicle", "lat", "lon",
                                                            "radius_m", "reason",  "auth"};
  for (const auto& [key, value] : body.items()) {
    if (std::find(kKeys.begin(), kKeys.end(), key) == kKeys.end()) {
      constexpr std::size_t kEchoBytes = 40;
      return Fail(why, key.substr(0, kEchoBytes) + ": unknown field");
    }
  }
  return true;
}

// `text`, an even number of hex digits, as bytes into `out` (out.size() * 2 digits).
bool FromHex(const std::string& text, std::span<std::uint8_t> out) {
  if (text.size() != 2 * out.size()) return false;
  const auto digit = [](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
  };
  for (std::size_t i = 0; i < out.size(); ++i) {
    const int high = digit(text[2 * i]);
    const int low = digit(text[2 * i + 1]);
    if (high < 0 || low < 0) return false;
    out[i] = static_cast<std::uint8_t>(high * 16 + low);
  }
  return true;
}

}  // namespace

std::optional<CommandCredentials> ParseWebCredentials(const nlohmann::json& body,
                                                      std::string* why) {
  const auto auth = body.is_object() ? body.find("auth") : body.end();
  if (!body.is_object() || auth == body.end()) {
    return Fail(why, "auth: required (the operator's signature: docs/command_center.md)"),
           std::nullopt;
  }
  if (!auth->is_object()) return Fail(why, "auth: must be a JSON object"), std::nullopt;
  for (const auto& [key, value] : auth->items()) {
    if (key != "operator" && key != "utime" && key != "nonce" && key != "mac") {
      constexpr std::size_t kEchoBytes = 40;
      return Fail(why, "auth." + key.substr(0, kEchoBytes) + ": unknown field"), std::nullopt;
    }
  }
  CommandCredentials credentials;
  const auto op = auth->find("operator");
  if (op == auth->end() || !op->is_string() ||
      !IsValidOperatorId(op->get_ref<const std::string&>())) {
    return Fail(why, "auth.operator: must be 1..64 of A-Z a-z 0-9 _ . -"), std::nullopt;
  }
  credentials.operator_id = op->get<std::string>();
  const auto utime = auth->find("utime");
  if (utime == auth->end() || !utime->is_number_integer() ||
      (utime->is_number_unsigned() && utime->get<std::uint64_t>() > INT64_MAX)) {
    return Fail(why, "auth.utime: must be an integer, microseconds"), std::nullopt;
  }
  credentials.utime = utime->get<std::int64_t>();
  std::array<std::uint8_t, 8> nonce{};
  const auto nonce_text = auth->find("nonce");
  if (nonce_text == auth->end() || !nonce_text->is_string() ||
      !FromHex(nonce_text->get_ref<const std::string&>(), nonce)) {
    return Fail(why, "auth.nonce: must be 16 hex digits"), std::nullopt;
  }
  std::uint64_t nonce_bits = 0;
  for (const std::uint8_t b : nonce) nonce_bits = (nonce_bits << 8) | b;
  credentials.nonce = static_cast<std::int64_t>(nonce_bits);
  const auto mac = auth->find("mac");
  if (mac == auth->end() || !mac->is_string() ||
      !FromHex(mac->get_ref<const std::string&>(), credentials.mac)) {
    return Fail(why, "auth.mac: must be 64 hex digits"), std::nullopt;
  }
  return credentials;
}

nlohmann::json WebCredentialsJson(const CommandCredentials& credentials) {
  static constexpr char kDigits[] = "0123456789abcdef";
  const auto hex = [](std::span<const std::uint8_t> bytes) {
    std::string text;
    for (const std::uint8_t b : bytes) {
      text += kDigits[b >> 4];
      text += kDigits[b & 15];
    }
    return text;
  };
  std::array<std::uint8_t, 8> nonce{};
  auto bits = static_cast<std::uint64_t>(credentials.nonce);
  for (auto b = nonce.rbegin(); b != nonce.rend(); ++b, bits >>= 8) {
    *b = static_cast<std::uint8_t>(bits);
  }
  return {{"operator", credentials.operator_id},
          {"utime", credentials.utime},
          {"nonce", hex(nonce)},
          {"mac", hex(credentials.mac)}};
}

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
