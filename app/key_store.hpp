// Where fireswarm keeps radio keys, one layout for every command:
//   fleet key store (fireswarm keys init DIR), directories 0700, files 0600:
//     DIR/broadcast.key                the fleet broadcast key (frames to receiver 255)
//     DIR/vehicles/<id>.key            one per vehicle, <id> = 1..254 in decimal
//     DIR/vehicles/<id>.previous.key   during a rotation: the key the vehicle may still use
//     DIR/operators/<name>.key         one per operator (operator commands)
//   a vehicle's own, next to its parameter file PATH (fireswarm keys provision):
//     PATH.key, PATH.broadcast.key, PATH.previous.key, PATH.radio-state
// Every key goes through common::ReadSecretKeyFile/WriteSecretKeyFile, which refuse
// key files that group or others may read.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "fireswarm/radio/frame_security.hpp"

namespace fireswarm::app {

namespace fs = std::filesystem;

fs::path BroadcastKeyPath(const fs::path& store);
fs::path VehicleKeyPath(const fs::path& store, int id);
fs::path PreviousVehicleKeyPath(const fs::path& store, int id);
fs::path OperatorKeyPath(const fs::path& store, const std::string& name);

/// The vehicle's files next to its parameter file (".key", ".broadcast.key", ...).
fs::path BesideParamFile(const fs::path& param_file, const std::string& suffix);

/// The server's radio security: the broadcast key and the key of each of `ids` from
/// `store` (with its previous key during a rotation), its counter and replay floors
/// persisted in `state_file`. Throws std::runtime_error naming a missing or unsafe
/// key file ("fireswarm keys add-vehicle" makes one).
std::shared_ptr<radio::FrameSecurity> ServerSecurityFromStore(const fs::path& store,
                                                              const std::vector<int>& ids,
                                                              const fs::path& state_file);

/// Vehicle `id`'s radio security from the fleet key store (simulated vehicles of
/// `fireswarm sim`); its counter persisted in `state_file`, or nowhere when empty.
std::shared_ptr<radio::FrameSecurity> VehicleSecurityFromStore(const fs::path& store, int id,
                                                               const fs::path& state_file);

/// Vehicle `id`'s radio security from the files provisioned next to its parameter
/// file; its counter and replay floor persisted there too. Throws std::runtime_error
/// naming a missing or unsafe key file.
std::shared_ptr<radio::FrameSecurity> VehicleSecurityFromParamFile(const fs::path& param_file,
                                                                   int id);

}  // namespace fireswarm::app
