#include "sim_link_flags.hpp"

#include <iostream>

#include "cli.hpp"
#include "fireswarm/common/camera_model.hpp"
#include "fireswarm/common/time.hpp"
#include "key_store.hpp"

namespace fireswarm::app {

void CheckSimRunFlags(const std::string& command, const SimRunFlags& f) {
  if (f.duration_s) {
    CheckFlagRange(command, "duration-s", *f.duration_s, {0.0, kMaxCommandDurationS, true});
  }
  if (!(f.speed >= kMinSpeed && f.speed <= kMaxSpeed)) {
    ThrowBadFlag(command, "speed", "in [1, 1000]", FlagText(f.speed));
  }
}

agents::VehicleConfig VehicleConfigFor(int id, const LinkFlags& link, const std::string& camera) {
  agents::VehicleConfig config;
  config.id = static_cast<std::uint8_t>(id);
  config.radio.id = config.id;
  config.radio.mode = ModeOf(link);
  config.radio.checksum = ChecksumOf(link);
  if (IsSecure(link) && !link.keys.empty()) {
    try {
      config.radio.security = VehicleSecurityFromStore(link.keys, id, {});
    } catch (const std::runtime_error& e) {
      throw UsageError(std::string("fireswarm: vehicle ") + std::to_string(id) + ": " + e.what());
    }
  }
  config.radio.timing.baud = static_cast<int>(link.baud);
  config.camera = common::CameraModelByName(camera);
  return config;
}

void RunFleet(SimulatedFleet& fleet, const OpenedLink& link, const LinkFlags& link_flags,
              const SimRunFlags& f) {
  if (link_flags.print_bound_port) {
    std::cout << "bound_port=" << link.udp->local_port() << std::endl;
  }
  fleet.Run(*link.link, f.speed,
            f.duration_s ? std::optional<common::Nanos>(common::FromSeconds(*f.duration_s))
                         : std::nullopt);
}

}  // namespace fireswarm::app
