#include "fireswarm/server/operator_keys.hpp"

#include <stdexcept>
#include <system_error>

#include "fireswarm/server/command_auth.hpp"

namespace fireswarm::server {

std::map<std::string, common::SecretKey> LoadOperatorKeys(const std::filesystem::path& key_store) {
  const std::filesystem::path dir = key_store / kOperatorKeysDir;
  std::error_code error;
  if (!std::filesystem::is_directory(dir, error)) {
    throw std::runtime_error(dir.string() +
                             ": no operator key directory (create keys with `fireswarm keys "
                             "operator NAME`)");
  }
  std::map<std::string, common::SecretKey> keys;
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
  if (keys.empty()) throw std::runtime_error(dir.string() + ": holds no <operator>.key file");
  return keys;
}

}  // namespace fireswarm::server
