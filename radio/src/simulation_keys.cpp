#include "fireswarm/radio/simulation_keys.hpp"

#include <random>
#include <utility>

namespace fireswarm::radio {

common::SecretKey SimulationKey(std::uint64_t seed, std::uint8_t key_id) {
  // A seeded generator, not a CSPRNG: these keys protect nothing, they only make a
  // simulated fleet run the secure code path.
  constexpr std::uint64_t kSimulationKeySalt = 0x5ECF'1EE7'0000'0000ULL;
  std::mt19937_64 generator(seed ^ kSimulationKeySalt ^ key_id);
  common::SecretKey key{};
  for (std::uint8_t& byte : key) byte = static_cast<std::uint8_t>(generator() >> 56U);
  return key;
}

std::shared_ptr<FrameSecurity> SimulationServerSecurity(std::uint64_t seed,
                                                        std::span<const std::uint8_t> vehicles) {
  auto security = std::make_shared<FrameSecurity>(ServerSecurityConfig(), SecurityState{},
                                                  PersistSecurityState{});
  for (const std::uint8_t id : vehicles) security->SetKey(id, SimulationKey(seed, id));
  security->SetKey(kBroadcastKeyId, SimulationKey(seed, kBroadcastKeyId));
  return security;
}

std::shared_ptr<FrameSecurity> SimulationVehicleSecurity(std::uint64_t seed, std::uint8_t id,
                                                         SecurityState restored,
                                                         PersistSecurityState persist) {
  auto security = std::make_shared<FrameSecurity>(VehicleSecurityConfig(id), std::move(restored),
                                                  std::move(persist));
  security->SetKey(id, SimulationKey(seed, id));
  security->SetKey(kBroadcastKeyId, SimulationKey(seed, kBroadcastKeyId));
  return security;
}

}  // namespace fireswarm::radio
