// Records what was on the simulated air during a run, for `radio-decode`,
// `lcm-logplayer` and later analysis. Two forms:
//  - a raw capture: the bytes of every transmission that was not lost to a
//    collision, in the order they ended (what a receiver that hears everything
//    without loss gets); `fireswarm radio-decode` reads it;
//  - an LCM log: one fireswarm.radio_frame_t event per transmission (collided ones
//    too, flagged) on channel RADIO_AIR, timestamped with the simulated end time.
// Files are written beside their final path and renamed into place by Commit(), so
// a run that fails leaves nothing half-written.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "fireswarm/radio/channel.hpp"

namespace fireswarm::app {

/// LCM channel of the radio_frame_t events.
inline constexpr const char* kAirLcmChannel = "RADIO_AIR";

class AirCapture {
 public:
  /// Opens the temporary files (common::OutputFiles). Throws std::runtime_error
  /// naming a path that cannot be written or is not a regular file.
  AirCapture(std::optional<std::string> raw_path, std::optional<std::string> lcm_log_path);
  ~AirCapture();
  AirCapture(const AirCapture&) = delete;
  AirCapture& operator=(const AirCapture&) = delete;

  /// Records one resolved transmission (an AirObserver).
  void Record(const radio::AirRecord& record);

  /// Flushes and moves every file to its final path. Throws std::runtime_error on an I/O error.
  void Commit();

 private:
  struct Files;
  std::unique_ptr<Files> files_;
};

}  // namespace fireswarm::app
