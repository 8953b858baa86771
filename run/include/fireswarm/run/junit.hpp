// The JUnit XML file of `fireswarm run`: each `expect` assertion of the scenario as
// one test case, so that a CI server shows a scenario's outcome like a test suite's.
#pragma once

#include <filesystem>
#include <string>

#include "fireswarm/run/report.hpp"

namespace fireswarm::run {

/// The report's expectations as JUnit XML: `<testsuites>` holding one
/// `<testsuite name="<scenario>">` (tests, failures, errors="0", time = the run's
/// wall-clock seconds, and properties seed, sim_seconds, coverage) with one
/// `<testcase classname="fireswarm.run.<scenario>" name="<assertion>">` per entry of
/// `report.expect`, in order. A failed one holds `<failure message="...">` with the
/// value, the limit and the detail; a passed one its value and limit as
/// `<system-out>`. Without expectations the suite holds one passing test case,
/// "scenario_runs" (the run finished). All text is XML-escaped; output is
/// deterministic for a given report.
std::string JunitXml(const Report& report);

/// Writes JunitXml(report) to `path` atomically (common::WriteFileAtomically).
/// Throws std::runtime_error naming the path when it cannot be written.
void WriteJunit(const Report& report, const std::filesystem::path& path);

}  // namespace fireswarm::run
