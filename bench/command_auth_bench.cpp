// Forged and replayed operator commands against the server core (issue 17's
// figure: 0 accepted of >= 10^4), and the cost of verifying one command.
//
//   command_auth_bench [--count N] [--check]
//
// A server with one operator ("ann") and one vehicle first takes 100 genuine
// signed holds; then N attacks, N/5 of each kind, go through
// Server::HandleSigned: a forged MAC (random tag), an unknown operator (signed
// with its own key), stale (ann's key, utime 31 s outside the window either
// way), a replay (a genuine command sent again within the window), and one bit
// flipped anywhere in a fresh genuine command (its fields, operator ID, utime,
// nonce or tag). Prints one JSON line: attacks and accepted per kind, and the
// CommandVerifier's time per genuine and per forged command (ns, best of 5
// rounds of N each). --check exits 1 when any attack was accepted.
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "fireswarm/server/command_auth.hpp"
#include "fireswarm/server/server.hpp"

namespace {

using fireswarm::common::SecretKey;
using fireswarm::server::CommandVerdict;
using fireswarm::server::CommandVerifier;
using fireswarm::server::OperatorCommand;
using fireswarm::server::Server;
using fireswarm::server::SignCommand;
using fireswarm::server::SignedCommand;

constexpr std::int64_t kUtimeNow = 1'764'000'000'000'000;  // the server's LCM clock, us
constexpr std::int64_t kOutsideUs = 31'000'000;            // beyond the 30 s window
constexpr int kGenuine = 100;
constexpr int kTimingRounds = 5;

SecretKey RandomKey(std::mt19937_64& random) {
  SecretKey key{};
  for (std::uint8_t& b : key) b = static_cast<std::uint8_t>(random());
  return key;
}

OperatorCommand Hold(int i) {
  OperatorCommand command;
  command.kind = OperatorCommand::Kind::kHold;
  command.vehicle = 1;
  command.reason = "hold " + std::to_string(i);
  return command;
}

// Flips bit `bit` of one field of `c`, chosen by `field`.
void FlipBit(SignedCommand& c, std::uint64_t field, std::uint64_t bit) {
  const auto flip = [&](auto& value) {
    using T = std::remove_reference_t<decltype(value)>;
    value = static_cast<T>(value ^ (T{1} << (bit % (8 * sizeof(T)))));
  };
  const auto flip_double = [&](double& value) {
    auto bits = std::bit_cast<std::uint64_t>(value);
    flip(bits);
    value = std::bit_cast<double>(bits);
  };
  switch (field % 9) {
    case 0: {
      auto kind = static_cast<std::uint8_t>(c.command.kind);
      flip(kind);
      c.command.kind = static_cast<OperatorCommand::Kind>(kind);
      break;
    }
    case 1:
      flip(c.command.vehicle);
      break;
    case 2:
      flip_double(c.command.point.lat_deg);
      break;
    case 3:
      flip_double(c.command.point.lon_deg);
      break;
    case 4:
      flip_double(c.command.radius_m);
      break;
    case 5: {
      char& ch = c.command.reason[bit % c.command.reason.size()];
      ch = static_cast<char>(ch ^ (1 << (bit % 8)));
      break;
    }
    case 6: {
      char& ch = c.credentials.operator_id[bit % c.credentials.operator_id.size()];
      ch = static_cast<char>(ch ^ (1 << (bit % 8)));
      break;
    }
    case 7:
      flip(bit % 2 == 0 ? c.credentials.utime : c.credentials.nonce);
      break;
    default:
      flip(c.credentials.mac[bit % c.credentials.mac.size()]);
      break;
  }
}

// Best of kTimingRounds: ns per Verify over `commands` (fresh verifier per round).
double VerifyNs(const std::map<std::string, SecretKey>& keys,
                const std::vector<SignedCommand>& commands) {
  double best = 1e18;
  for (int round = 0; round < kTimingRounds; ++round) {
    CommandVerifier verifier(keys);
    std::size_t accepted = 0;
    const auto start = std::chrono::steady_clock::now();
    for (const SignedCommand& c : commands) {
      accepted += verifier.Verify(c, kUtimeNow) == CommandVerdict::kAccepted ? 1U : 0U;
    }
    const std::chrono::duration<double, std::nano> took = std::chrono::steady_clock::now() - start;
    best = std::min(best, took.count() / static_cast<double>(commands.size()));
    if (accepted > commands.size()) std::abort();  // keeps the loop's result alive
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  int count = 20'000;
  bool check = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--count" && i + 1 < argc) {
      count = std::atoi(argv[++i]);
    } else if (arg == "--check") {
      check = true;
    } else {
      std::cerr << "command_auth_bench: unknown argument '" << arg
                << "' (usage: command_auth_bench [--count N] [--check])\n";
      return 2;
    }
  }
  if (count < 5) {
    std::cerr << "command_auth_bench: --count must be >= 5\n";
    return 2;
  }
  std::mt19937_64 random(17);
  const SecretKey ann = RandomKey(random);
  fireswarm::server::ServerConfig config;
  config.operators = {{"ann", ann}};
  Server server(config, fireswarm::common::LocalFrame{{46.0, -74.5}});
  server.AddVehicle(1);
  std::int64_t nonce = 0;
  std::vector<SignedCommand> genuine;
  for (int i = 0; i < kGenuine; ++i) {
    genuine.push_back(SignCommand(Hold(i), "ann", ann, kUtimeNow - i, ++nonce));
    if (!server.HandleSigned(genuine.back(), {}, kUtimeNow)) {
      std::cerr << "command_auth_bench: a genuine command was refused\n";
      return 1;
    }
  }
  const std::size_t records = server.commands().size();

  const std::array<const char*, 5> kinds = {"forged_mac", "unknown_operator", "stale", "replayed",
                                            "bit_flipped"};
  std::map<std::string, std::pair<int, int>> outcome;  // kind -> attacks, accepted
  for (int i = 0; i < count; ++i) {
    const int kind = i % 5;
    SignedCommand attack;
    switch (kind) {
      case 0:
        attack = SignCommand(Hold(i), "ann", ann, kUtimeNow, ++nonce);
        for (std::uint8_t& b : attack.credentials.mac) b = static_cast<std::uint8_t>(random());
        break;
      case 1:
        attack = SignCommand(Hold(i), "mallory", RandomKey(random), kUtimeNow, ++nonce);
        break;
      case 2:
        attack = SignCommand(Hold(i), "ann", ann, kUtimeNow + (i % 2 ? kOutsideUs : -kOutsideUs),
                             ++nonce);
        break;
      case 3:
        attack = genuine[static_cast<std::size_t>(i) % genuine.size()];
        break;
      default:
        attack = SignCommand(Hold(i), "ann", ann, kUtimeNow, ++nonce);
        FlipBit(attack, random(), random());
        break;
    }
    auto& [attacks, accepted] = outcome[kinds.at(static_cast<std::size_t>(kind))];
    ++attacks;
    accepted += server.HandleSigned(attack, {}, kUtimeNow) ? 1 : 0;
    if (i % 1'000 == 0) server.TakeJournalEntries();  // as an adapter appends them
  }
  int accepted_total = 0;
  nlohmann::ordered_json line;
  line["event"] = "command_auth_bench";
  line["attacks"] = count;
  for (const auto& [kind, figures] : outcome) {
    line[kind] = {{"attacks", figures.first}, {"accepted", figures.second}};
    accepted_total += figures.second;
  }
  line["accepted"] = accepted_total;
  line["records_added"] = server.commands().size() - records;
  line["refusals_counted"] = server.refusal_count();

  std::vector<SignedCommand> fresh;
  std::vector<SignedCommand> forged;
  for (int i = 0; i < count; ++i) {
    fresh.push_back(SignCommand(Hold(i), "ann", ann, kUtimeNow, i + 1));
    forged.push_back(fresh.back());
    forged.back().credentials.mac[0] ^= 1;
  }
  line["verify_genuine_ns"] = VerifyNs(config.operators, fresh);
  line["verify_forged_ns"] = VerifyNs(config.operators, forged);
  std::cout << line.dump() << std::endl;
  const bool failed = accepted_total > 0 || server.commands().size() != records;
  return check && failed ? 1 : 0;
}
