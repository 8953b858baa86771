#include "key_store.hpp"

#include <stdexcept>

#include "fireswarm/common/secret_key.hpp"
#include "fireswarm/radio/security_state_file.hpp"

namespace fireswarm::app {

fs::path BroadcastKeyPath(const fs::path& store) {
  return store / "broadcast.key";
}

fs::path VehicleKeyPath(const fs::path& store, int id) {
  return store / "vehicles" / (std::to_string(id) + ".key");
}

fs::path PreviousVehicleKeyPath(const fs::path& store, int id) {
  return store / "vehicles" / (std::to_string(id) + ".previous.key");
}

fs::path OperatorKeyPath(const fs::path& store, const std::string& name) {
  return store / "operators" / (name + ".key");
}

fs::path BesideParamFile(const fs::path& param_file, const std::string& suffix) {
  return fs::path(param_file.string() + suffix);
}

namespace {

std::shared_ptr<radio::FrameSecurity> MakeSecurity(const radio::FrameSecurityConfig& config,
                                                   const fs::path& state_file) {
  if (state_file.empty()) {
    return std::make_shared<radio::FrameSecurity>(config, radio::SecurityState{},
                                                  radio::PersistSecurityState{});
  }
  return std::make_shared<radio::FrameSecurity>(config, radio::ReadSecurityStateFile(state_file),
                                                radio::PersistToFile(state_file));
}

}  // namespace

std::shared_ptr<radio::FrameSecurity> ServerSecurityFromStore(const fs::path& store,
                                                              const std::vector<int>& ids,
                                                              const fs::path& state_file) {
  auto security = MakeSecurity(radio::ServerSecurityConfig(), state_file);
  security->SetKey(radio::kBroadcastKeyId, common::ReadSecretKeyFile(BroadcastKeyPath(store)));
  for (const int id : ids) {
    const auto key_id = static_cast<std::uint8_t>(id);
    security->SetKey(key_id, common::ReadSecretKeyFile(VehicleKeyPath(store, id)));
    const fs::path previous = PreviousVehicleKeyPath(store, id);
    if (fs::exists(previous)) security->SetPreviousKey(key_id, common::ReadSecretKeyFile(previous));
  }
  return security;
}

std::shared_ptr<radio::FrameSecurity> VehicleSecurityFromStore(const fs::path& store, int id,
                                                               const fs::path& state_file) {
  const auto key_id = static_cast<std::uint8_t>(id);
  auto security = MakeSecurity(radio::VehicleSecurityConfig(key_id), state_file);
  security->SetKey(key_id, common::ReadSecretKeyFile(VehicleKeyPath(store, id)));
  security->SetKey(radio::kBroadcastKeyId, common::ReadSecretKeyFile(BroadcastKeyPath(store)));
  return security;
}

std::shared_ptr<radio::FrameSecurity> VehicleSecurityFromParamFile(const fs::path& param_file,
                                                                   int id) {
  const auto key_id = static_cast<std::uint8_t>(id);
  auto security = MakeSecurity(radio::VehicleSecurityConfig(key_id),
                               BesideParamFile(param_file, ".radio-state"));
  security->SetKey(key_id, common::ReadSecretKeyFile(BesideParamFile(param_file, ".key")));
  security->SetKey(radio::kBroadcastKeyId,
                   common::ReadSecretKeyFile(BesideParamFile(param_file, ".broadcast.key")));
  const fs::path previous = BesideParamFile(param_file, ".previous.key");
  if (fs::exists(previous)) security->SetPreviousKey(key_id, common::ReadSecretKeyFile(previous));
  return security;
}

}  // namespace fireswarm::app
