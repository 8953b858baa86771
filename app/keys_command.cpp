// `fireswarm keys ACTION DIR`: the fleet key store (key_store.hpp gives the layout).
//   init DIR                              create DIR (0700) and its broadcast key
//   add-vehicle DIR --id N [--id M ...]   a key per vehicle (refuses to overwrite)
//   add-operator DIR --name NAME          an operator's key (operator commands)
//   provision DIR --id N --param-file P   copy vehicle N's keys next to its parameter
//                                         file P (P.key, P.broadcast.key), as over its
//                                         wired link before a sortie
//   rotate DIR --id N                     new key for N, the old one kept as previous
//   retire DIR --id N                     drop N's previous key once N uses the new one
// Every key file is written 0600 from its first byte; a key file others may read is
// refused (common::ReadSecretKeyFile). docs/protocol.md "Keys" gives the procedures.
#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli.hpp"
#include "commands.hpp"
#include "fireswarm/common/secret_key.hpp"
#include "key_store.hpp"

namespace fireswarm::app {
namespace {

namespace po = boost::program_options;
using Json = nlohmann::ordered_json;

constexpr const char* kName = "keys";
constexpr fs::perms kOwnerOnlyDir = fs::perms::owner_all;

struct KeysFlags {
  std::string action;
  std::string store;
  std::vector<int> ids;
  std::string name;
  std::string param_file;
};

[[noreturn]] void Bad(const std::string& what) {
  throw UsageError(std::string("fireswarm keys: ") + what);
}

// Creates `dir` (and its parents) and makes it 0700; refuses a directory others may enter.
void MakeOwnerOnlyDirectory(const fs::path& dir) {
  fs::create_directories(dir);
  fs::permissions(dir, kOwnerOnlyDir, fs::perm_options::replace);
}

void RequireStore(const fs::path& store) {
  if (!fs::is_directory(store) || !fs::exists(BroadcastKeyPath(store))) {
    Bad("'" + store.string() + "' is not a key store (create one with 'fireswarm keys init " +
        store.string() + "')");
  }
}

int OneId(const KeysFlags& f) {
  if (f.ids.size() != 1) Bad("--id must be given once for '" + f.action + "'");
  return f.ids.front();
}

void Print(const std::string& event, const fs::path& path) {
  std::cout << Json{{"event", event}, {"path", path.string()}}.dump() << std::endl;
}

void Init(const fs::path& store) {
  MakeOwnerOnlyDirectory(store);
  MakeOwnerOnlyDirectory(store / "vehicles");
  MakeOwnerOnlyDirectory(store / "operators");
  const fs::path broadcast = BroadcastKeyPath(store);
  if (fs::exists(broadcast)) {
    common::ReadSecretKeyFile(broadcast);  // still a valid, owner-only key
    Print("kept", broadcast);
    return;
  }
  common::WriteSecretKeyFile(broadcast, common::GenerateSecretKey());
  Print("created", broadcast);
}

void AddVehicles(const fs::path& store, const std::vector<int>& ids) {
  if (ids.empty()) Bad("add-vehicle needs --id N (1..254), once per vehicle");
  for (const int id : ids) {
    const fs::path path = VehicleKeyPath(store, id);
    if (fs::exists(path))
      Bad("vehicle " + std::to_string(id) + " already has a key (" + path.string() +
          "); use 'rotate' to replace it");
  }
  for (const int id : ids) {
    common::WriteSecretKeyFile(VehicleKeyPath(store, id), common::GenerateSecretKey());
    Print("created", VehicleKeyPath(store, id));
  }
}

void AddOperator(const fs::path& store, const std::string& name) {
  constexpr std::size_t kMaxOperatorName = 64;
  const auto allowed = [](char c) {
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '-';
  };
  if (name.empty() || name.size() > kMaxOperatorName ||
      !std::all_of(name.begin(), name.end(), allowed)) {
    Bad("--name must be 1 to 64 letters, digits, '_' or '-', got '" + name + "'");
  }
  const fs::path path = OperatorKeyPath(store, name);
  if (fs::exists(path)) Bad("operator '" + name + "' already has a key (" + path.string() + ")");
  common::WriteSecretKeyFile(path, common::GenerateSecretKey());
  Print("created", path);
}

void Provision(const fs::path& store, int id, const fs::path& param_file) {
  if (param_file.empty()) Bad("provision needs --param-file PATH (the vehicle's parameter file)");
  const fs::path key = BesideParamFile(param_file, ".key");
  common::WriteSecretKeyFile(key, common::ReadSecretKeyFile(VehicleKeyPath(store, id)));
  Print("provisioned", key);
  const fs::path broadcast = BesideParamFile(param_file, ".broadcast.key");
  common::WriteSecretKeyFile(broadcast, common::ReadSecretKeyFile(BroadcastKeyPath(store)));
  Print("provisioned", broadcast);
  const fs::path previous = BesideParamFile(param_file, ".previous.key");
  if (fs::exists(PreviousVehicleKeyPath(store, id))) {
    common::WriteSecretKeyFile(previous,
                               common::ReadSecretKeyFile(PreviousVehicleKeyPath(store, id)));
    Print("provisioned", previous);
  } else if (fs::exists(previous)) {
    fs::remove(previous);
    Print("removed", previous);
  }
}

void Rotate(const fs::path& store, int id) {
  const fs::path current = VehicleKeyPath(store, id);
  const fs::path previous = PreviousVehicleKeyPath(store, id);
  if (fs::exists(previous)) {
    Bad("vehicle " + std::to_string(id) + " is still in a rotation (" + previous.string() +
        "); 'retire' it once the vehicle uses its new key");
  }
  const common::SecretKey old_key = common::ReadSecretKeyFile(current);
  common::WriteSecretKeyFile(previous, old_key);
  common::WriteSecretKeyFile(current, common::GenerateSecretKey());
  Print("rotated", current);
}

void Retire(const fs::path& store, int id) {
  const fs::path previous = PreviousVehicleKeyPath(store, id);
  if (!fs::exists(previous)) Bad("vehicle " + std::to_string(id) + " has no previous key");
  fs::remove(previous);
  Print("retired", previous);
}

}  // namespace

int RunKeys(const std::vector<std::string>& args) {
  KeysFlags f;
  po::options_description options("keys options");
  auto add = options.add_options();
  add("action", po::value(&f.action)->required(),
      "init, add-vehicle, add-operator, provision, rotate or retire");
  add("store", po::value(&f.store)->required(), "the fleet key store directory");
  add("id", po::value(&f.ids)->composing(), "vehicle receiver ID, 1..254 (repeat for several)");
  add("name", po::value(&f.name), "operator name (add-operator)");
  add("param-file", po::value(&f.param_file)->value_name("PATH"),
      "the vehicle's parameter file (provision): its keys go next to it");
  po::positional_options_description positional;
  positional.add("action", 1).add("store", 1);
  po::variables_map values;
  if (!ParseCommandLine(kName, "ACTION DIR [--id N] [--name NAME] [--param-file PATH]", options,
                        positional, args, values)) {
    return kExitOk;
  }
  for (const int id : f.ids) {
    if (id < 1 || id > 254) ThrowBadFlag(kName, "id", "in 1..254", std::to_string(id));
  }
  const fs::path store = f.store;
  try {
    if (f.action == "init") {
      Init(store);
      return kExitOk;
    }
    RequireStore(store);
    if (f.action == "add-vehicle") {
      AddVehicles(store, f.ids);
    } else if (f.action == "add-operator") {
      AddOperator(store, f.name);
    } else if (f.action == "provision") {
      Provision(store, OneId(f), f.param_file);
    } else if (f.action == "rotate") {
      Rotate(store, OneId(f));
    } else if (f.action == "retire") {
      Retire(store, OneId(f));
    } else {
      Bad("ACTION must be init, add-vehicle, add-operator, provision, rotate or retire, got '" +
          f.action + "'");
    }
  } catch (const fs::filesystem_error& e) {
    Bad(e.what());
  } catch (const std::runtime_error& e) {
    if (dynamic_cast<const UsageError*>(&e) != nullptr) throw;
    Bad(e.what());  // a missing or unsafe key file: bad input, named by ReadSecretKeyFile
  }
  return kExitOk;
}

}  // namespace fireswarm::app
