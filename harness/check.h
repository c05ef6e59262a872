// Reproducibility: re-run the config recorded in a results folder and compare every column, each
// by its kind (harness/columns.h): parameters and counts exactly, reference-dependent values
// within their declared tolerance, timings within a relative tolerance (reported, never a
// failure), context (device, driver, Embree's threads and ISA) reported.
#pragma once
#include <ostream>
#include <string>
#include <vector>

#include "config.h"
#include "writers.h"

namespace rtbench {

struct CheckOptions {
    double timingTolerance = 0.5;  // relative: 0.5 = within 50%
    // When non-empty, replaces baseline.embree_config in every run (e.g. "isa=sse4.2"): the
    // counts must not change with Embree's code path.
    std::string embreeConfigOverride;
};

struct CheckResult {
    int runs = 0;
    int deterministicDifferences = 0;  // parameters, counts, and reference values beyond tolerance
    int referenceDifferences = 0;      // reference-dependent values that differ within tolerance
    int timingDifferences = 0;         // timings outside the tolerance (reported, not failures)
    int contextDifferences = 0;        // reported, not failures
    bool failed() const { return deterministicDifferences > 0; }
};

// The plan a results folder's context (context.json, or a shard's) records: its config text,
// scenes resolved against the recorded config's folder (where it was when run if that still
// exists, else where the path points from here), with the command line's overrides.
ExperimentPlan recordedPlan(const Json& context, const std::string& contextPath);

// What would fail `check` between a recorded row and its re-run: parameters and exact columns that
// differ, reference-dependent values beyond their tolerance; one table line each (none: the same run).
std::vector<std::string> deterministicDifferences(const Row& recorded, const Row& rerun);

// Re-runs <folder>/context.json's config text (scenes resolve against the recorded config's
// folder) into a temporary folder, for the runs recorded in <folder>/runs.csv (an interrupted
// sweep checks what it finished), and compares row by row. Prints a table of what differs, with
// each difference's kind, to `out`. A malformed runs.csv (missing column, cut row, duplicate run,
// unclosed quote) is an error, not a pass.
CheckResult checkResults(const std::string& folder, const CheckOptions& options, std::ostream& out);

}  // namespace rtbench
