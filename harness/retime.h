// rtbench retime: re-time only the runs the noise guard flagged (a timing_warning) in a results
// folder recorded by this binary on this machine, and keep the better-conditioned timings.
//
// Each flagged run is re-run up to `tries` times, all flagged runs together in one scratch folder
// per try (so an interleaved sweep stays interleaved). A try whose parameters or counts differ
// from the record (what `rtbench check` fails on) is a failure and nothing is written. Otherwise
// the best try replaces the run's row and samples when it is better conditioned than the record:
// no timing warning beats one, then the narrower widest spread of its methods (a median's interval
// half-width; below 6 repetitions the CV).
// The `retimed` column says which try was kept and why, or that none was; the replaced rows and
// samples are saved aside (superseded-<time>-runs.csv and -samples.csv), never lost.
#pragma once
#include "schema/column.h"
#include <ostream>
#include <string>
#include <vector>

namespace rtbench {

struct RetimeOptions {
    int tries = 3;  // re-runs of each flagged run at most (1 to 100); a run stops once it times clean
};

struct RetimeResult {
    int flagged = 0;   // ok runs with a timing warning in the folder
    int replaced = 0;  // runs whose timings a better-conditioned try replaced
    int cleared = 0;   // of those, runs that now have no timing warning
    std::vector<std::string> differences;  // deterministic differences of a try (a failure: nothing written)
    bool failed() const { return !differences.empty(); }
};

// Throws rtbench::Error (nothing written) when the folder is not a complete results folder of
// this schema, or a flagged run was recorded by another commit or on another CPU.
// The column retime writes into each run it re-timed.
const Column<std::string>& retimedColumn();

RetimeResult retimeFlagged(const std::string& folder, const RetimeOptions& options, std::ostream& out);

}  // namespace rtbench
