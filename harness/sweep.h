// The sweep over a plan's runs: one after another (experiment.order = sequential), or interleaved:
// every run prepared, then timed one round at a time across the sweep (round r of every run before
// round r + 1 of any), then each finished. Each run's row is recorded as it ends: said on the
// console, its samples then its row appended to the folder's files, so an interrupt loses nothing
// done (and an interleaved sweep's finished rounds are in samples.csv as each ends).
#pragma once
#include <vector>

#include "harness/output_folder.h"
#include "harness/resume.h"
#include "harness/runner.h"

namespace rtbench {

// What the sweep works on: the plan's runs of this invocation (`mine`), in the files of a held
// folder, from what a resume kept; `result` gets the counts of failed, warned and reused runs.
struct Sweep {
    const ExperimentPlan& plan;
    const std::vector<const RunConfig*>& mine;
    const SweepFiles& files;
    const FolderIdentity& folder;
    const RunnerOptions& options;
    Caches& caches;
    Resumed& resumed;  // its rows are written in place
    ExperimentResult& result;
};

// Runs every run not kept, in the order experiment.order says.
void runSweep(Sweep& sweep);

}  // namespace rtbench
