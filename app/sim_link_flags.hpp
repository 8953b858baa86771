// The flags shared by the commands that fly simulated vehicles behind a real link
// (`vehicle`, `sim`; their run loop is sim_link_loop.hpp): --seed, --speed and
// --duration-s beside the link flags (link_flags.hpp); their checks, a vehicle's
// configuration from them, and the run. Each command declares the options itself,
// with its own help text and order.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "fireswarm/agents/vehicle.hpp"
#include "link_flags.hpp"
#include "sim_link_loop.hpp"

namespace fireswarm::app {

/// --speed bounds: below 1 the vehicles' clock would lag the airtimes they must
/// keep (sim_link_loop.hpp, "Time").
inline constexpr double kMinSpeed = 1.0;
inline constexpr double kMaxSpeed = 1000.0;

struct SimRunFlags {
  std::uint64_t seed = 1;            ///< the simulation's seed
  std::optional<double> duration_s;  ///< simulated s; nullopt: until SIGINT or SIGTERM
  double speed = 1.0;                ///< simulated time per wall time, kMinSpeed..kMaxSpeed
};

/// Throws UsageError ("fireswarm <command>: --speed must be ...") when --duration-s
/// is not > 0 or --speed is outside [kMinSpeed, kMaxSpeed].
void CheckSimRunFlags(const std::string& command, const SimRunFlags& flags);

/// Vehicle `id` carrying the camera model `camera`, talking the mode, checksum and
/// baud the link flags select; secure mode with its keys from --keys (counter in
/// memory). Preconditions: CheckLinkFlags passed, `camera` is a known model
/// (common::FindCameraModel). Throws UsageError naming a missing or unsafe key file.
agents::VehicleConfig VehicleConfigFor(int id, const LinkFlags& link, const std::string& camera);

/// Prints 'bound_port=<port>' on stdout when --print-bound-port asks for it (call it
/// once the vehicles are built, so whoever reads the port is answered at once),
/// then runs `fleet` on the link until a signal or --duration-s. Throws as
/// SimulatedFleet::Run.
void RunFleet(SimulatedFleet& fleet, const OpenedLink& link, const LinkFlags& link_flags,
              const SimRunFlags& flags);

}  // namespace fireswarm::app
