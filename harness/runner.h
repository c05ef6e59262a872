// Runs an experiment plan: for each run, scene -> grid -> kernel on Vulkan -> Embree on the same
// rays -> metrics -> one CSV row (+ context JSON, images). A failing run writes a row with
// status=failed and its reason; the other runs go on.
#pragma once
#include <string>
#include <vector>

#include "config.h"
#include "writers.h"

namespace rtbench {

struct RunnerOptions {
    std::string outputOverride;  // replaces experiment.output when non-empty
    std::string deviceOverride;  // replaces device.name when non-empty
    bool validationOverride = false;  // forces device.validation on
    bool quiet = false;
    std::string commandLine;  // recorded in context.json
};

struct ExperimentResult {
    std::string folder;     // <output>/<name>
    std::vector<Row> rows;  // as written to runs.csv
    int failed = 0;
};

ExperimentResult runExperiment(const ExperimentPlan& plan, const RunnerOptions& options);

// Column order of runs.csv: parameters first, then metrics.
std::vector<std::string> runColumns();

// The short table printed after a run (Mrays/s kernel vs Embree, agreement).
std::string summaryTable(const std::vector<Row>& rows);

}  // namespace rtbench
