// Checksums of byte ranges from running checksum states (private to the radio
// module). The parser checks a candidate frame at every preamble, and candidates
// may overlap heavily (a preamble every 4 bytes, each promising 263 bytes), so
// checksumming each candidate in full costs up to ~90 times the stream. Instead the
// parser keeps the running state after every buffered byte, computes each once, and
// gets any candidate's checksum from the states at its two ends in constant time.
//
// XOR: the XOR of a range is the XOR of the running states at its ends.
// CRC-16/CCITT-FALSE is affine in its register: n bytes d taken from register r
// leave r * x^(8n) + L(d) mod P (L linear, P the polynomial 0x1021 with x^16). So
// from one running CRC's states s_first and s_last n bytes apart, the CRC of the
// range alone (started from the initial value I) is s_last + (s_first + I) * x^(8n)
// mod P, where + is XOR.
#pragma once

#include <boost/crc.hpp>
#include <cstddef>
#include <cstdint>

#include "fireswarm/radio/frame.hpp"

namespace fireswarm::radio::detail {

/// The CRC-16/CCITT-FALSE register of frame.hpp (width 16, polynomial 0x1021, initial
/// value 0xFFFF, no reflection, no final XOR); Crc16() and the parser both use it.
using Crc16Register = boost::crc_optimal<16, 0x1021, 0xFFFF, 0, false, false>;

/// The state a running checksum starts from: 0 (XOR) or 0xFFFF (CRC-16, also secure mode).
std::uint16_t InitialChecksumState(ChecksumMode mode);

/// Sets states[i + 1] to the running checksum after bytes[i], for i in [from, to).
/// Precondition: states[from] holds the state before bytes[from].
void ExtendChecksumStates(ChecksumMode mode, const std::uint8_t* bytes, std::uint16_t* states,
                          std::size_t from, std::size_t to);

/// The checksum (Xor8() or Crc16() value) of the `size` bytes between two states of
/// one running checksum, `at_first` before the range and `at_last` after it.
/// Precondition: size <= kMaxFrameSize.
std::uint16_t ChecksumBetween(ChecksumMode mode, std::uint16_t at_first, std::uint16_t at_last,
                              std::size_t size);

}  // namespace fireswarm::radio::detail
