// Runs an experiment plan: for each run, scene -> rays -> acceleration structure -> the strategy's
// kernels on Vulkan -> Embree on the same rays -> references -> verdict -> one CSV row (+ context
// JSON, images). A failing run writes a row with
// status=failed and its reason; the other runs go on.
#pragma once
#include <set>
#include <string>
#include <vector>

#include "columns.h"
#include "config.h"
#include "writers.h"

namespace rtbench {

struct RunnerOptions {
    std::string outputOverride;  // replaces experiment.output when non-empty (-d and --validation
                                 // set device.* in the plan: overrideKey, harness/config.h)
    bool quiet = false;
    std::string commandLine;  // recorded in context.json
    // Resumption: runs whose ok row is already in the output's CSV with the same identity (run
    // number, config hash, git commit, device and driver, and the contents of the scene's files)
    // are kept, not re-run, unless `force`. Rows that are not kept are saved aside in
    // superseded-<time>-runs.csv, never lost.
    bool force = false;
    // Sharding: run only the runs whose index % shardCount == shardIndex, into
    // runs.shard-<i>-of-<n>.csv (`rtbench merge` joins the shards).
    unsigned shardIndex = 0, shardCount = 1;
    // Run only these run numbers ("007"); empty: all (rtbench check re-runs what was recorded).
    std::set<std::string> onlyRuns;
    // --filter: run only the runs matching every filter (plan_view.h filterRuns); the rows an
    // earlier invocation wrote for the plan's other runs stay in runs.csv as they are.
    std::vector<std::string> filters;
};

struct ExperimentResult {
    std::string folder;     // <output>/<name>
    std::vector<Row> rows;  // as written to runs.csv
    int failed = 0;
    int reused = 0;  // rows kept from an earlier invocation (resumption)
    int warned = 0;  // runs with a warning or a timing warning (each said on stderr unless quiet)
};

ExperimentResult runExperiment(const ExperimentPlan& plan, const RunnerOptions& options);

// The files a run writes: runs.csv, samples.csv and context.json, or runs.shard-<i>-of-<n>.csv,
// samples.shard-<i>-of-<n>.csv and context.shard-<i>-of-<n>.json for a shard.
std::string runsFileName(const RunnerOptions& options);
std::string contextFileName(const RunnerOptions& options);
// Every timed repetition of every run, long format (harness/timing_rounds.h): samples.csv, or
// samples.shard-<i>-of-<n>.csv for a shard.
std::string samplesFileName(const RunnerOptions& options);

// A run's number as it appears in the CSV and file names: "000", "001", ...
std::string runNumber(const RunConfig& run);

// A run's row before it runs: its parameters and identity (run, label, sweep, config_hash, the
// binary's commit, the device and CPU it runs on).
Row identityRow(const RunConfig& run, const std::string& commit, const std::string& device, const std::string& driver,
                const std::string& cpu);

// A number for the console: 3 significant digits (whole numbers from 100 on); other text as it is.
std::string consoleNumber(const std::string& cell);

// The short table printed after a run (Mrays/s kernel vs Embree, agreement), numbers by consoleNumber.
std::string summaryTable(const std::vector<Row>& rows);

}  // namespace rtbench
