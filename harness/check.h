// Reproducibility: re-run the config recorded in a results folder and compare every column.
#pragma once
#include <ostream>
#include <string>

namespace rtbench {

// Columns that measure time (compared within a tolerance) rather than count (compared exactly).
bool isTimingColumn(const std::string& column);

struct CheckResult {
    int runs = 0;
    int deterministicDifferences = 0;  // counts, passes, bytes, agreement, grid stats, status ...
    int timingDifferences = 0;         // timings outside the tolerance (reported, not failures)
};

// Re-runs <folder>/context.json's config text (scenes resolve against the recorded config's
// folder) into a temporary folder and compares it row by row with <folder>/runs.csv. Prints a
// table of what differs to `out`. `timingTolerance` is relative (0.5 = within 50%). Where the
// machine differs (device, driver, Embree's threads or ISA) that is reported as context; counts
// that depend on it (lane counts depend on the subgroup size) then differ too.
CheckResult checkResults(const std::string& folder, double timingTolerance, std::ostream& out);

}  // namespace rtbench
