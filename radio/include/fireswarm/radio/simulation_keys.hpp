// Secure mode for simulated fleets (fireswarm run, sim-bench, radio-bench, tests):
// keys derived deterministically from the scenario seed and the key ID, held in
// memory only, nothing persisted. FOR SIMULATION ONLY: anyone who knows the seed
// knows the keys. A real link takes its keys from a key store (fireswarm keys).
// Key bytes never change simulated behaviour (frame sizes are fixed, decryption
// returns the same payload), so a run's result does not depend on them.
#pragma once

#include <cstdint>
#include <memory>
#include <span>

#include "fireswarm/common/secret_key.hpp"
#include "fireswarm/radio/frame_security.hpp"

namespace fireswarm::radio {

/// The simulation key of `key_id` (a vehicle's ID, or kBroadcastKeyId) for `seed`.
common::SecretKey SimulationKey(std::uint64_t seed, std::uint8_t key_id);

/// The server's security with the simulation keys of `vehicles` and the broadcast key.
std::shared_ptr<FrameSecurity> SimulationServerSecurity(std::uint64_t seed,
                                                        std::span<const std::uint8_t> vehicles);

/// Vehicle `id`'s security with its simulation key and the broadcast key; a
/// vehicle restarting passes the state it persisted (its counter and replay
/// floors) and where to persist the next one (FrameSecurity's constructor).
std::shared_ptr<FrameSecurity> SimulationVehicleSecurity(std::uint64_t seed, std::uint8_t id,
                                                         SecurityState restored = {},
                                                         PersistSecurityState persist = {});

}  // namespace fireswarm::radio
