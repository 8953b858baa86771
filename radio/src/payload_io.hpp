// The three visitors that payload_layouts.hpp walks a message with (private to the
// radio module): PayloadSizeCounter counts wire bytes at compile time,
// PayloadWriter encodes, PayloadReader decodes. Each offers the same field methods,
// so one layout function per message defines its wire format for all three.
#pragma once

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "byte_io.hpp"
#include "fireswarm/radio/messages.hpp"
#include "fixed_point.hpp"

namespace fireswarm::radio::detail {

/// Counts the wire bytes of a layout; usable in constant expressions.
class PayloadSizeCounter {
 public:
  constexpr void Header(const MessageHeader& /*header*/) { size_ += 3; }
  template <std::integral Int>
  constexpr void Integer(const Int& /*value*/) {
    size_ += sizeof(Int);
  }
  template <std::integral Wire>
  constexpr void Fixed(const double& /*value*/, double /*units_per_unit*/,
                       WireRange<Wire> /*range*/) {
    size_ += sizeof(Wire);
  }
  constexpr void Heading(const double& /*heading_deg*/) { size_ += 2; }
  constexpr void ClampedU16(const std::uint32_t& /*value*/) { size_ += 2; }
  constexpr void Float32(const float& /*value*/) { size_ += 4; }
  template <typename Enum>
  constexpr void EnumValue(const Enum& /*value*/, Enum /*first*/, Enum /*last*/) {
    size_ += 1;
  }
  constexpr void Count(const std::uint8_t& /*count*/, std::size_t /*capacity*/,
                       const char* /*field*/) {
    size_ += 1;
  }
  constexpr std::size_t size() const { return size_; }

 private:
  std::size_t size_ = 0;
};

/// Appends the wire bytes of each field to a vector.
class PayloadWriter {
 public:
  explicit PayloadWriter(std::vector<std::uint8_t>& out) : out_(out) {}

  void Header(const MessageHeader& header) {
    Integer(header.sender);
    Integer(header.sequence);
  }
  template <std::integral Int>
  void Integer(const Int& value) {
    AppendLittleEndian(out_, value);
  }
  /// Rounds `value * units_per_unit` and clamps it into `range`.
  template <std::integral Wire>
  void Fixed(const double& value, double units_per_unit, WireRange<Wire> range) {
    AppendLittleEndian(out_, ToFixed(value, units_per_unit, range));
  }
  void Heading(const double& heading_deg) {
    AppendLittleEndian(out_, HeadingToCentidegrees(heading_deg));
  }
  /// A u32 in the struct that travels as u16: clamped to 65,535.
  void ClampedU16(const std::uint32_t& value) {
    AppendLittleEndian(out_, static_cast<std::uint16_t>(std::min<std::uint32_t>(value, 0xFFFF)));
  }
  void Float32(const float& value) {
    AppendLittleEndian(out_, std::bit_cast<std::uint32_t>(value));
  }
  /// Written as is; a value outside [first, last] fails to decode at the receiver.
  template <typename Enum>
  void EnumValue(const Enum& value, Enum /*first*/, Enum /*last*/) {
    AppendLittleEndian(out_, static_cast<std::uint8_t>(value));
  }
  /// Throws std::invalid_argument when `count` exceeds the struct's capacity.
  void Count(const std::uint8_t& count, std::size_t capacity, const char* field) {
    if (count > capacity) {
      throw std::invalid_argument(std::string("EncodePayload: ") + field + " " +
                                  std::to_string(count) + " exceeds the capacity of " +
                                  std::to_string(capacity));
    }
    Integer(count);
  }

 private:
  std::vector<std::uint8_t>& out_;
};

/// Reads each field from a payload whose length was checked against the layout.
/// Never reads past the span; an out-of-range value sets bad_value().
class PayloadReader {
 public:
  explicit PayloadReader(std::span<const std::uint8_t> bytes) : reader_(bytes) {}

  void Header(MessageHeader& header) {
    Integer(header.sender);
    Integer(header.sequence);
  }
  template <std::integral Int>
  void Integer(Int& value) {
    value = reader_.Read<Int>();
  }
  /// Wire values outside `range` are bad values (the encoder never writes them).
  template <std::integral Wire>
  void Fixed(double& value, double units_per_unit, WireRange<Wire> range) {
    const Wire wire = reader_.Read<Wire>();
    if (wire < range.min || wire > range.max) bad_value_ = true;
    value = FromFixed(wire, units_per_unit);
  }
  /// 36,000 centidegrees and above are bad values: the encoder wraps into [0, 360).
  void Heading(double& heading_deg) {
    const auto wire = reader_.Read<std::uint16_t>();
    if (wire >= kCentidegreesPerTurn) bad_value_ = true;
    heading_deg = FromFixed(wire, kCentiPerUnit);
  }
  void ClampedU16(std::uint32_t& value) { value = reader_.Read<std::uint16_t>(); }
  void Float32(float& value) { value = std::bit_cast<float>(reader_.Read<std::uint32_t>()); }
  template <typename Enum>
  void EnumValue(Enum& value, Enum first, Enum last) {
    const auto wire = reader_.Read<std::uint8_t>();
    if (wire < static_cast<std::uint8_t>(first) || wire > static_cast<std::uint8_t>(last)) {
      bad_value_ = true;
    }
    value = static_cast<Enum>(wire);
  }
  /// A count above the capacity is a bad value and reads as 0, so the entries that
  /// follow are not read into the struct (and the length check then fails).
  void Count(std::uint8_t& count, std::size_t capacity, const char* /*field*/) {
    count = reader_.Read<std::uint8_t>();
    if (count > capacity) {
      bad_value_ = true;
      count = 0;
    }
  }

  bool bad_value() const { return bad_value_; }
  /// True when the layout did not consume exactly the payload's bytes.
  bool length_mismatch() const { return reader_.overrun() || reader_.remaining() != 0; }

 private:
  LittleEndianReader reader_;
  bool bad_value_ = false;
};

}  // namespace fireswarm::radio::detail
