#include "link_flags.hpp"

#include <iostream>

#include "cli.hpp"

namespace fireswarm::app {

namespace po = boost::program_options;

void AddLinkOptions(po::options_description& options, LinkFlags& f) {
  auto add = options.add_options();
  add("udp", po::value(&f.udp)->multitoken()->composing()->value_name("LOCAL REMOTE"),
      "UDP link: bind LOCAL (host:port, port 0 = any) and send to REMOTE (host:port); serve: "
      "once per radio channel");
  add("serial", po::value(&f.serial)->composing()->value_name("DEVICE"),
      "serial link: the modem's device; serve: once per radio channel");
  add("baud", po::value(&f.baud)->default_value(f.baud),
      "serial speed, 8N1 (with --serial); turn timing assumes it on both ends");
  add("mode", po::value(&f.mode)->default_value(f.mode), "poll or slots, on both ends");
  add("checksum", po::value(&f.checksum)->default_value(f.checksum),
      "secure (AES-256-GCM, keys from --keys), crc16 or xor (unsecured: anyone on the "
      "channel can command the fleet), on both ends");
  add("keys", po::value(&f.keys)->value_name("DIR"),
      "the fleet key store (fireswarm keys init DIR): vehicle keys for --checksum secure; "
      "serve also takes its operators' keys from DIR/operators/");
  add("print-bound-port", po::bool_switch(&f.print_bound_port),
      "print 'bound_port=<port>' on stdout once the UDP link is bound");
}

// The fastest serial line a modem is driven at (docs/limits.md).
constexpr double kMaxSerialBaud = 4'000'000.0;

void CheckLinkFlags(const std::string& command, const LinkFlags& f,
                    const po::variables_map& values, std::size_t max_links) {
  const std::string prefix = "fireswarm " + command + ": ";
  const bool udp = values.count("udp") != 0U;
  const bool serial = values.count("serial") != 0U;
  if (udp == serial) {
    throw UsageError(prefix +
                     "give exactly one link, --udp LOCAL REMOTE or --serial DEVICE (see "
                     "'fireswarm " +
                     command + " --help')");
  }
  if (udp && (f.udp.empty() || f.udp.size() % 2 != 0)) {
    throw UsageError(prefix + "--udp must be two endpoints, LOCAL REMOTE (host:port each), got " +
                     std::to_string(f.udp.size()) + " values");
  }
  if (LinkCount(f) > max_links) {
    throw UsageError(prefix + (max_links == 1 ? std::string("give one link, got ")
                                              : "give at most " + std::to_string(max_links) +
                                                    " links (one per radio channel), got ") +
                     std::to_string(LinkCount(f)));
  }
  if (!serial && !values["baud"].defaulted()) {
    throw UsageError(prefix + "--baud goes with --serial");
  }
  CheckFlagRange(command, "baud", f.baud, {1.0, kMaxSerialBaud});
  if (f.print_bound_port && !udp) {
    throw UsageError(prefix + "--print-bound-port goes with --udp");
  }
  if (!radio::ParseLinkMode(f.mode)) {
    throw UsageError(prefix + "--mode must be poll or slots, got '" + f.mode + "'");
  }
  if (!radio::ParseChecksumMode(f.checksum)) {
    throw UsageError(prefix + "--checksum must be secure, crc16 or xor, got '" + f.checksum + "'");
  }
}

std::size_t LinkCount(const LinkFlags& f) {
  return f.serial.empty() ? f.udp.size() / 2 : f.serial.size();
}

OpenedLink OpenLink(const LinkFlags& f, std::size_t index) {
  OpenedLink opened;
  if (f.serial.empty()) {
    auto udp = std::make_unique<radio::UdpLink>(f.udp.at(2 * index), f.udp.at(2 * index + 1));
    opened.udp = udp.get();
    opened.link = std::move(udp);
  } else {
    opened.link = radio::OpenSerialLink(f.serial.at(index), f.baud);
  }
  return opened;
}

radio::LinkMode ModeOf(const LinkFlags& f) {
  return *radio::ParseLinkMode(f.mode);
}

radio::ChecksumMode ChecksumOf(const LinkFlags& f) {
  return *radio::ParseChecksumMode(f.checksum);
}

bool IsSecure(const LinkFlags& f) {
  return ChecksumOf(f) == radio::ChecksumMode::kSecure;
}

void RequireKeys(const std::string& command, const LinkFlags& f) {
  if (IsSecure(f) && f.keys.empty()) {
    throw UsageError("fireswarm " + command +
                     ": --checksum secure (the default) needs --keys DIR, the fleet key store "
                     "(create one with 'fireswarm keys init DIR' and 'fireswarm keys add-vehicle "
                     "DIR --id N'); --checksum crc16 runs the link unsecured");
  }
}

void WarnIfUnsecured(const std::string& command, const LinkFlags& f) {
  if (IsSecure(f)) return;
  std::cerr << "fireswarm " << command << ": WARNING: the radio link runs UNSECURED (--checksum "
            << f.checksum
            << "): anyone on the channel can upload missions, send vehicles home, rewrite their "
               "parameters and forge fire reports. Use --checksum secure --keys DIR."
            << std::endl;
}

}  // namespace fireswarm::app
