// Alerts from transitions between consecutive vehicle states and track lists.
#include "command_center_alerts.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace fireswarm::server::internal {

namespace {

std::string_view LevelName(AlertLevel level) {
  switch (level) {
    case AlertLevel::kInfo:
      return "info";
    case AlertLevel::kWarning:
      return "warning";
    case AlertLevel::kCritical:
      return "critical";
  }
  return "info";
}

std::string Drone(int id) {
  return "drone " + std::to_string(id);
}

std::string Percent(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.0f %%", value);
  return text;
}

}  // namespace

void AlertLog::Add(double time_s, AlertLevel level, std::string_view kind, int vehicle, int track,
                   std::string text) {
  alerts_.push_back({{"id", next_id_++},
                     {"time_s", time_s},
                     {"level", LevelName(level)},
                     {"kind", kind},
                     {"vehicle", vehicle},
                     {"track", track},
                     {"text", std::move(text)}});
  if (alerts_.size() > kept_) alerts_.pop_front();
  unsent_ = std::min(unsent_ + 1, alerts_.size());
}

nlohmann::json AlertLog::All() const {
  nlohmann::json all = nlohmann::json::array();
  for (const nlohmann::json& alert : alerts_) all.push_back(alert);
  return all;
}

nlohmann::json AlertLog::TakeNew() {
  nlohmann::json fresh = nlohmann::json::array();
  for (std::size_t i = alerts_.size() - unsent_; i < alerts_.size(); ++i) {
    fresh.push_back(alerts_[i]);
  }
  unsent_ = 0;
  return fresh;
}

bool BatteryLow(const vehicle_state_t& m) {
  if (m.telemetry_age_s < 0.0) return false;
  if ((m.flags & vehicle_state_t::FLAG_LOW_BATTERY) != 0) return true;
  return m.flight_mode == vehicle_state_t::MODE_RETURN_TO_LAUNCH &&
         m.battery_percent <= kLowBatteryPercent;
}

void RaiseVehicleAlerts(const vehicle_state_t* previous, const vehicle_state_t& now,
                        AlertLog& log) {
  const double time_s = static_cast<double>(now.utime) * 1e-6;
  const int id = now.receiver_id;
  const int link_before = previous ? previous->link_state : vehicle_state_t::LINK_NEVER_HEARD;
  if (now.link_state != link_before) {
    // Degraded is news coming from a good (or no) link, not on the way back from lost.
    if (now.link_state == vehicle_state_t::LINK_DEGRADED &&
        link_before != vehicle_state_t::LINK_LOST) {
      log.Add(time_s, AlertLevel::kWarning, "link_degraded", id, 0, Drone(id) + ": link degraded");
    } else if (now.link_state == vehicle_state_t::LINK_LOST) {
      log.Add(time_s, AlertLevel::kCritical, "link_lost", id, 0, Drone(id) + ": link lost");
    }
  }
  const bool low_before = previous != nullptr && BatteryLow(*previous);
  if (BatteryLow(now) && !low_before) {
    log.Add(time_s, AlertLevel::kWarning, "battery_low", id, 0,
            Drone(id) + ": battery low (" + Percent(now.battery_percent) + ")");
  }
  const int task_before = previous ? previous->task : vehicle_state_t::TASK_IDLE;
  if (now.task == vehicle_state_t::TASK_GIVEN_UP && task_before != vehicle_state_t::TASK_GIVEN_UP) {
    log.Add(time_s, AlertLevel::kWarning, "vehicle_given_up", id, 0,
            Drone(id) + ": given up, it does not answer");
  }
}

void RaiseChannelAlerts(const nlohmann::json& previous_radio, const radio_stats_t& now,
                        double time_s, AlertLog& log) {
  const std::size_t channels = std::min(now.channel_silent.size(), now.channel_vehicles.size());
  for (std::size_t k = 0; k < channels; ++k) {
    bool was_silent = false;
    if (previous_radio.is_object() && previous_radio.contains("channels") &&
        k < previous_radio["channels"].size()) {
      was_silent = previous_radio["channels"][k].value("silent", false);
    }
    const std::string name = "radio channel " + std::to_string(k);
    if (now.channel_silent[k] && !was_silent) {
      log.Add(time_s, AlertLevel::kCritical, "channel_silent", 0, 0,
              name + ": silent, none of its " + std::to_string(now.channel_vehicles.at(k)) +
                  " vehicles answers (modem or link down?)");
    } else if (!now.channel_silent[k] && was_silent) {
      log.Add(time_s, AlertLevel::kInfo, "channel_heard", 0, 0, name + ": heard again");
    }
  }
}

void RaiseTrackAlerts(std::optional<int> previous_status, const fire_track_t& track, double time_s,
                      AlertLog& log) {
  const int id = track.track_id;
  const int first_drone = track.vehicle_ids.empty() ? 0 : track.vehicle_ids.front();
  if (!previous_status && track.status != fire_track_t::STATUS_REJECTED) {
    std::string text = "fire " + std::to_string(id) + ": new";
    if (first_drone != 0) text += ", reported by " + Drone(first_drone);
    log.Add(time_s, AlertLevel::kWarning, "new_fire", first_drone, id, std::move(text));
  }
  if (track.status == fire_track_t::STATUS_CONFIRMED &&
      previous_status.value_or(fire_track_t::STATUS_TENTATIVE) != fire_track_t::STATUS_CONFIRMED) {
    log.Add(time_s, AlertLevel::kCritical, "fire_confirmed", 0, id,
            "fire " + std::to_string(id) + ": confirmed");
  }
}

bool IsAirborne(const vehicle_state_t& m) {
  return m.has_position && m.telemetry_age_s >= 0.0 &&
         m.flight_mode != vehicle_state_t::MODE_IDLE &&
         m.flight_mode != vehicle_state_t::MODE_LANDED && std::isfinite(m.altitude_m) &&
         m.altitude_m > kAirborneMinAltitudeM;
}

}  // namespace fireswarm::server::internal
