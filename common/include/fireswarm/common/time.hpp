// Time, one way for the whole tree. Simulated time is exact integer nanoseconds
// since the scenario start; real links use the steady clock since the process
// start. Integer nanoseconds keep airtimes and lockstep steps exact (1 ns) and
// deterministic. The seed's controllers count their loop intervals in
// microseconds (Arduino micros()); `Micros` carries that unit in the type.
#pragma once

#include <chrono>

namespace fireswarm::common {

/// Simulated or link time, integer nanoseconds.
using Nanos = std::chrono::nanoseconds;
/// A loop interval in (fractional) microseconds, as the seed's PID takes it.
using Micros = std::chrono::duration<double, std::micro>;

inline constexpr double kMillisPerSecond = 1e3;
inline constexpr double kMicrosPerSecond = 1e6;

/// Converts seconds to nanoseconds, rounded to the nearest. Precondition: finite.
inline Nanos FromSeconds(double seconds) {
  return std::chrono::round<Nanos>(std::chrono::duration<double>(seconds));
}

/// Converts nanoseconds to seconds as a double, for figures and JSON.
constexpr double ToSeconds(Nanos t) {
  return static_cast<double>(t.count()) * 1e-9;
}

/// Converts nanoseconds to fractional microseconds (count / 1000, as a double).
constexpr Micros ToMicros(Nanos t) {
  return std::chrono::duration_cast<Micros>(t);
}

}  // namespace fireswarm::common
