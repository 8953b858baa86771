// The headers every subcommand's file parses, precompiled once for the
// executable (app/CMakeLists.txt): Boost.Geometry and Eigen (through the planner's
// and the run's headers), Boost.Program_options, nlohmann-json and the standard
// library. Parsing was half of each file's compile time; with this header
// run_command.cpp compiles in 7.7 s of CPU instead of 14.0 (-O2).
// Nothing here is ours: a file still includes what it uses.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <boost/geometry.hpp>
#include <boost/program_options.hpp>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>
#include <variant>
#include <vector>
