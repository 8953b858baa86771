#include "fireswarm/server/operator_keys.hpp"

#include <stdexcept>
#include <system_error>

#include "fireswarm/server/command_auth.hpp"

namespace fireswarm::server {

std::map<std::string, common::SecretKey> LoadOperatorKeys(const std::filesystem::path& key_store) {
  const std::filesystem::path dir = key_store / kOperatorKeysDir;
  std::error_code error;
  std::map<std::string, common::SecretKey> keys;
  if (!std::filesystem::is_directory(key_store, error)) {
    throw std::runtime_error(key_store.string() +
                             ": no key store (create one with `fireswarm keys init DIR`)");
  }
  // A store may hold vehicle keys only (a mission started with --start): no
  // operators, so every command is refused (the caller says so).
  if (!std::filesystem::exists(dir, error)) return keys;
  if (!std::filesystem::is_directory(dir, error)) {
    throw std::runtime_error(dir.string() +
                             ": not a directory (create operator keys with "
                             "`fireswarm keys add-operator`)");
  }
  for (const std::filesystem::directory_entry& entry :
       std::filesystem::directory_iterator(dir, error)) {
    const std::filesystem::path& path = entry.path();
    if (path.extension() != ".key") continue;
    const std::string id = path.stem().string();
    if (!IsValidOperatorId(id)) {
      throw std::runtime_error(path.string() +
                               ": not a valid operator ID (1..64 of A-Z a-z 0-9 _ . -)");
    }
    keys.emplace(id, common::ReadSecretKeyFile(path));
  }
  if (error) throw std::runtime_error(dir.string() + ": cannot list: " + error.message());
  return keys;
}

}  // namespace fireswarm::server
