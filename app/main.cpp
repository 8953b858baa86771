// fireswarm: command center for a fleet of fire-search drones.
// `fireswarm <subcommand> [options]`; `fireswarm <subcommand> --help` for each.

#include <array>
#include <exception>
#include <iostream>
#include <new>
#include <string>
#include <string_view>
#include <vector>

#include "cli.hpp"
#include "commands.hpp"

namespace {

using fireswarm::app::Command;

constexpr std::array kCommands{
    Command{"keys", "create the fleet key store, add, provision and rotate radio and operator keys",
            fireswarm::app::RunKeys},
    Command{"params", "list the vehicle's parameters (IDs, ranges), or a vehicle's parameter file",
            fireswarm::app::RunParams},
    Command{"plan", "plan the fleet's search of a GeoJSON area; write GeoJSON and QGC .plan files",
            fireswarm::app::RunPlan},
    Command{"radio-bench", "simulate N vehicles on one half-duplex channel and print link figures",
            fireswarm::app::RunRadioBench},
    Command{"radio-decode", "decode a raw APOne byte capture into one JSON line per frame",
            fireswarm::app::RunRadioDecode},
    Command{"replay", "show a recorded mission (LCM log) on the command-center page, read-only",
            fireswarm::app::RunReplay},
    Command{"run", "fly a scenario file headless in simulated time; write the scored report",
            fireswarm::app::RunRun},
    Command{"serve", "run the command server on the wall clock over a serial or UDP radio link",
            fireswarm::app::RunServe},
    Command{"sim", "fly N simulated vehicles behind one real serial or UDP link, for serve",
            fireswarm::app::RunSim},
    Command{"sim-bench", "fly N drones with thermal cameras over a burning area; print the speed",
            fireswarm::app::RunSimBench},
    Command{"sweep", "fly a scenario over many seeds and variants; summary with plots (local or Slurm)",
            fireswarm::app::RunSweep},
    Command{"vehicle", "fly one simulated vehicle behind a real serial or UDP link (HIL)",
            fireswarm::app::RunVehicle},
};

void PrintUsage(std::ostream& out) {
  out << "usage: fireswarm <subcommand> [options]\n\nsubcommands:\n";
  for (const Command& command : kCommands) {
    out << "  " << command.name << std::string(16 - std::string_view(command.name).size(), ' ')
        << command.summary << "\n";
  }
  out << "\n'fireswarm <subcommand> --help' describes each one.\n";
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> words(argv + 1, argv + argc);
  if (words.empty()) {
    PrintUsage(std::cerr);
    return fireswarm::app::kExitBadInput;
  }
  if (words[0] == "--help" || words[0] == "-h" || words[0] == "help") {
    PrintUsage(std::cout);
    return fireswarm::app::kExitOk;
  }
  for (const Command& command : kCommands) {
    if (words[0] != command.name) continue;
    try {
      return command.run(std::vector<std::string>(words.begin() + 1, words.end()));
    } catch (const fireswarm::app::UsageError& e) {
      std::cerr << e.what() << "\n";
      return fireswarm::app::kExitBadInput;
    } catch (const std::bad_alloc&) {
      // A last resort: every input that sizes the work has a documented limit
      // (docs/limits.md) checked before the work starts.
      std::cerr << "fireswarm " << command.name
                << ": out of memory while running the command; see docs/limits.md for the "
                   "limits of its flags and inputs\n";
      return fireswarm::app::kExitBadInput;
    } catch (const std::exception& e) {
      std::cerr << "fireswarm " << command.name << ": " << e.what() << "\n";
      return fireswarm::app::kExitBadInput;
    }
  }
  std::cerr << "fireswarm: unknown subcommand '" << words[0] << "'\n\n";
  PrintUsage(std::cerr);
  return fireswarm::app::kExitBadInput;
}
