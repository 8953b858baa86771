// A sweep's directory (`fireswarm sweep --out DIR`): DIR/plan.json, each run's
// DIR/runs/<id>/ (scenario.yaml, report.json, output.txt, record.json) and the
// summary files. A run is done once its record.json is there (written atomically
// after the run ended), which is all a resumed sweep and --collect go by.
#pragma once

#include <filesystem>
#include <optional>

#include "child_pool.hpp"
#include "fireswarm/run/sweep.hpp"
#include "fireswarm/run/sweep_summary.hpp"

namespace fireswarm::app {

/// DIR/runs/<id>/.
std::filesystem::path RunDir(const std::filesystem::path& out, std::size_t id);

/// The run's committed record, or nullopt when it has none (or one that does not
/// read back, which only a disk fault leaves: the run is then done again).
std::optional<run::RunRecord> ReadRecord(const std::filesystem::path& out, std::size_t id);

/// The record of a run that ended as `end` (its files in `dir`; `timeout_s` as given).
run::RunRecord MakeRecord(const run::SweepRun& sweep_run, const ChildEnd& end,
                          const std::filesystem::path& dir, std::optional<double> timeout_s);

/// Writes DIR/plan.json, or checks that the one there is this plan. Throws
/// UsageError when DIR cannot be made or holds another sweep's plan.
void WritePlan(const std::filesystem::path& out, const run::SweepPlan& plan);

/// Writes DIR/summary.{json,csv,html} from the plan and the runs' records and
/// reports, naming the runs without a result on stderr. Returns 0 when every run
/// is done, 1 otherwise. Throws UsageError when DIR holds no readable plan.
int Collect(const std::filesystem::path& out);

}  // namespace fireswarm::app
