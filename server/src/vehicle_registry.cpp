#include "fireswarm/server/vehicle_registry.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace fireswarm::server {

std::string_view ToString(LinkState state) {
  switch (state) {
    case LinkState::kNeverHeard:
      return "never_heard";
    case LinkState::kOk:
      return "ok";
    case LinkState::kDegraded:
      return "degraded";
    case LinkState::kLost:
      return "lost";
  }
  return "unknown";
}

VehicleRegistry::VehicleRegistry(LinkThresholds thresholds) : thresholds_(thresholds) {
  const bool valid = std::isfinite(thresholds.degraded_after_s) &&
                     std::isfinite(thresholds.lost_after_s) && thresholds.degraded_after_s > 0.0 &&
                     thresholds.degraded_after_s < thresholds.lost_after_s;
  if (!valid) {
    throw std::invalid_argument(
        "vehicle registry: link thresholds need 0 < degraded_after_s < lost_after_s, got "
        "degraded_after_s = " +
        std::to_string(thresholds.degraded_after_s) +
        ", lost_after_s = " + std::to_string(thresholds.lost_after_s));
  }
}

void VehicleRegistry::Register(int receiver_id) {
  if (receiver_id < kFirstVehicleId || receiver_id > kLastVehicleId) {
    throw std::invalid_argument("vehicle registry: receiver ID " + std::to_string(receiver_id) +
                                " is outside " + std::to_string(kFirstVehicleId) + ".." +
                                std::to_string(kLastVehicleId));
  }
  const auto id = static_cast<std::uint8_t>(receiver_id);
  if (vehicles_[id]) {
    throw std::invalid_argument("vehicle registry: receiver ID " + std::to_string(receiver_id) +
                                " is already registered");
  }
  vehicles_[id].emplace().id = id;
  ++size_;
}

bool VehicleRegistry::Contains(std::uint8_t receiver_id) const {
  return vehicles_[receiver_id].has_value();
}

VehicleState* VehicleRegistry::Find(std::uint8_t receiver_id) {
  std::optional<VehicleState>& vehicle = vehicles_[receiver_id];
  return vehicle ? &*vehicle : nullptr;
}

const VehicleState& VehicleRegistry::Get(std::uint8_t receiver_id) const {
  const std::optional<VehicleState>& vehicle = vehicles_[receiver_id];
  if (!vehicle) {
    throw std::out_of_range("vehicle registry: receiver ID " + std::to_string(receiver_id) +
                            " is not registered");
  }
  return *vehicle;
}

bool VehicleRegistry::OnTelemetry(const radio::Telemetry& telemetry, double now_s) {
  VehicleState* vehicle = Find(telemetry.header.sender);
  if (vehicle == nullptr || !std::isfinite(now_s)) return false;
  if (vehicle->telemetry && now_s < vehicle->telemetry_time_s) return false;
  vehicle->telemetry = telemetry;
  vehicle->telemetry_time_s = now_s;
  return OnReply(telemetry.header.sender, now_s);
}

bool VehicleRegistry::OnReply(std::uint8_t receiver_id, double now_s) {
  VehicleState* vehicle = Find(receiver_id);
  if (vehicle == nullptr || !std::isfinite(now_s)) return false;
  vehicle->missed_replies = 0;
  ++vehicle->total_replies;
  // A reply handled out of order must not make the link look older than it is.
  vehicle->last_heard_s = std::max(vehicle->last_heard_s.value_or(now_s), now_s);
  return true;
}

bool VehicleRegistry::OnMissedReply(std::uint8_t receiver_id) {
  VehicleState* vehicle = Find(receiver_id);
  if (vehicle == nullptr) return false;
  ++vehicle->missed_replies;
  ++vehicle->total_missed_replies;
  return true;
}

const VehicleState& VehicleRegistry::state(std::uint8_t receiver_id) const {
  return Get(receiver_id);
}

LinkState VehicleRegistry::LinkOf(const VehicleState& vehicle, double now_s) const {
  if (!vehicle.last_heard_s) return LinkState::kNeverHeard;
  const double silence_s = now_s - *vehicle.last_heard_s;
  if (silence_s >= thresholds_.lost_after_s) return LinkState::kLost;
  if (silence_s >= thresholds_.degraded_after_s) return LinkState::kDegraded;
  return LinkState::kOk;
}

LinkState VehicleRegistry::LinkAt(std::uint8_t receiver_id, double now_s) const {
  return LinkOf(Get(receiver_id), now_s);
}

std::optional<double> VehicleRegistry::TelemetryAgeS(std::uint8_t receiver_id, double now_s) const {
  const VehicleState& vehicle = Get(receiver_id);
  if (!vehicle.telemetry) return std::nullopt;
  return std::max(0.0, now_s - vehicle.telemetry_time_s);
}

std::vector<std::uint8_t> VehicleRegistry::ids() const {
  std::vector<std::uint8_t> out;
  out.reserve(size_);
  for (const std::optional<VehicleState>& vehicle : vehicles_) {
    if (vehicle) out.push_back(vehicle->id);
  }
  return out;
}

std::vector<std::uint8_t> VehicleRegistry::IdsWhere(double now_s, bool (*keep)(LinkState)) const {
  std::vector<std::uint8_t> out;
  for (const std::optional<VehicleState>& vehicle : vehicles_) {
    if (vehicle && keep(LinkOf(*vehicle, now_s))) out.push_back(vehicle->id);
  }
  return out;
}

std::vector<std::uint8_t> VehicleRegistry::LostAt(double now_s) const {
  return IdsWhere(now_s, [](LinkState link) { return link == LinkState::kLost; });
}

std::vector<std::uint8_t> VehicleRegistry::ActiveAt(double now_s) const {
  return IdsWhere(
      now_s, [](LinkState link) { return link == LinkState::kOk || link == LinkState::kDegraded; });
}

}  // namespace fireswarm::server
