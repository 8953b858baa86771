// The subcommands of the `fireswarm` executable. Each lives in its own
// <name>_command.cpp and is listed once in main.cpp.
#pragma once

#include <string>
#include <vector>

namespace fireswarm::app {

int RunRadioDecode(const std::vector<std::string>& args);
int RunRadioBench(const std::vector<std::string>& args);
int RunPlan(const std::vector<std::string>& args);
int RunSimBench(const std::vector<std::string>& args);
int RunVehicle(const std::vector<std::string>& args);
int RunParams(const std::vector<std::string>& args);
int RunRun(const std::vector<std::string>& args);
int RunReplay(const std::vector<std::string>& args);
int RunServe(const std::vector<std::string>& args);
int RunSim(const std::vector<std::string>& args);
int RunKeys(const std::vector<std::string>& args);
int RunSweep(const std::vector<std::string>& args);

}  // namespace fireswarm::app
