// Conversions between engineering units (double) and the protocol's fixed-point
// wire integers (private to the radio module). Encoding rounds to nearest (half
// away from zero) and clamps to the wire range, so no input - huge, infinite or
// NaN - has undefined behaviour; NaN encodes as 0.
#pragma once

#include <cmath>
#include <concepts>
#include <cstdint>
#include <limits>

namespace fireswarm::radio::detail {

/// Wire units per engineering unit, one constant per scale in docs/protocol.md.
inline constexpr double kE7PerDegree = 1e7;        // lat/lon: 1e-7 degree
inline constexpr double kCentiPerUnit = 100.0;     // cm per m, cm/s per m/s, 0.01 degree
inline constexpr double kDeciPerUnit = 10.0;       // dm per m, 0.1 m/s, 0.1 degree Celsius
inline constexpr double kMilliPerUnit = 1000.0;    // mV per V
inline constexpr double kCorrelationSteps = 1e4;   // correlation: 1e-4
inline constexpr double kConfidenceSteps = 255.0;  // confidence: 1/255
inline constexpr std::uint16_t kCentidegreesPerTurn = 36'000;

/// The wire integer type of a fixed-point field and the range it may take.
template <std::integral Wire>
struct WireRange {
  Wire min = std::numeric_limits<Wire>::min();
  Wire max = std::numeric_limits<Wire>::max();
};
inline constexpr WireRange<std::int32_t> kI32{};
inline constexpr WireRange<std::int16_t> kI16{};
inline constexpr WireRange<std::uint16_t> kU16{};
inline constexpr WireRange<std::uint8_t> kU8{};

/// Rounds `value * units_per_unit` to the nearest integer in `range` (which holds 0).
template <std::integral Wire>
Wire ToFixed(double value, double units_per_unit, WireRange<Wire> range) {
  const double scaled = std::round(value * units_per_unit);
  if (std::isnan(scaled)) return 0;
  if (scaled <= static_cast<double>(range.min)) return range.min;
  if (scaled >= static_cast<double>(range.max)) return range.max;
  return static_cast<Wire>(scaled);
}

/// The engineering value of a wire integer. Division by the exact scale gives the
/// double nearest to the true value, so a value on the wire grid (47.1234567 deg)
/// decodes to exactly the literal that encoded it.
template <std::integral Wire>
double FromFixed(Wire wire, double units_per_unit) {
  return static_cast<double>(wire) / units_per_unit;
}

/// A heading in degrees wrapped into [0, 360) and rounded to 0.01 degree; a value
/// that rounds up to 360.00 wraps to 0. NaN and infinities encode as 0.
inline std::uint16_t HeadingToCentidegrees(double heading_deg) {
  // fmod is exact, so wrapping first keeps precision for any finite input.
  constexpr double kTurn = kCentidegreesPerTurn;
  double centidegrees = std::round(std::fmod(heading_deg, 360.0) * kCentiPerUnit);
  if (std::isnan(centidegrees)) return 0;
  if (centidegrees < 0.0) centidegrees += kTurn;
  if (centidegrees >= kTurn) centidegrees -= kTurn;
  return static_cast<std::uint16_t>(centidegrees);
}

}  // namespace fireswarm::radio::detail
