// The radio-link flags shared by the commands that talk over a real link
// (`vehicle`, `sim`, `serve`): --udp LOCAL REMOTE | --serial DEVICE [--baud B],
// --mode, --checksum, --keys, --print-bound-port; their checks and the link they open.
#pragma once

#include <boost/program_options.hpp>
#include <memory>
#include <string>
#include <vector>

#include "fireswarm/radio/discipline.hpp"
#include "fireswarm/radio/link.hpp"
#include "fireswarm/radio/udp_link.hpp"

namespace fireswarm::app {

struct LinkFlags {
  std::vector<std::string> udp;     ///< LOCAL REMOTE, LOCAL REMOTE, ... (one pair per link)
  std::vector<std::string> serial;  ///< devices, one per link; empty = none
  unsigned baud = 57'600;
  std::string mode = "slots";
  /// secure (the default; issue 17), crc16 or xor.
  std::string checksum = "secure";
  /// The fleet key store (key_store.hpp), for --checksum secure; empty = none.
  std::string keys;
  bool print_bound_port = false;
};

/// Adds the link options to `options`, writing into `flags` (which must outlive them).
void AddLinkOptions(boost::program_options::options_description& options, LinkFlags& flags);

/// Throws UsageError naming the flag ("fireswarm <command>: --mode ...") unless
/// one link is given (or, with `max_links` > 1, 1..max_links of one kind: one
/// radio channel each) and every link flag is valid.
void CheckLinkFlags(const std::string& command, const LinkFlags& flags,
                    const boost::program_options::variables_map& values,
                    std::size_t max_links = 1);

/// How many links the flags give. Precondition: CheckLinkFlags passed.
std::size_t LinkCount(const LinkFlags& flags);

/// The link the flags name, opened; `udp` points into it for a UDP link.
struct OpenedLink {
  std::unique_ptr<radio::IoLink> link;
  radio::UdpLink* udp = nullptr;
};
/// Link `index` (0: the first --serial or --udp pair). Throws as
/// radio::OpenSerialLink and radio::UdpLink. Precondition: CheckLinkFlags passed.
OpenedLink OpenLink(const LinkFlags& flags, std::size_t index = 0);

/// The link timing, mode and checksum the flags select. Precondition: CheckLinkFlags passed.
radio::LinkMode ModeOf(const LinkFlags& flags);
radio::ChecksumMode ChecksumOf(const LinkFlags& flags);

/// Whether the flags secure the link (--checksum secure).
bool IsSecure(const LinkFlags& flags);

/// Throws UsageError ("fireswarm <command>: --checksum secure needs --keys DIR ...")
/// when the link is secured but no key store is given.
void RequireKeys(const std::string& command, const LinkFlags& flags);

/// Prints the loud warning of an unsecured real link on stderr (once, at start).
void WarnIfUnsecured(const std::string& command, const LinkFlags& flags);

}  // namespace fireswarm::app
