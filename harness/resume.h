// Resumption: which rows of an earlier invocation of the sweep stand (ok, and the same run in every
// input: harness/runner.h RunnerOptions::force), which are set aside (never lost: a
// superseded-<time>-* file of their own, with the samples and files that were theirs), and which
// finished rounds of an interleaved sweep's runs the timing goes on from.
#pragma once
#include <map>
#include <string>
#include <vector>

#include "harness/config.h"
#include "harness/run_inputs.h"
#include "harness/runner.h"

namespace rtbench {

// The files one invocation writes in its results folder (runs.csv, samples.csv, context.json, or
// a shard's) and the columns of runs.csv.
struct SweepFiles {
    std::string folder;
    std::string csvName, csvPath;
    std::string samplesName, samplesPath;
    std::string contextPath;
    std::vector<std::string> columns;
};

// What this invocation starts from.
struct Resumed {
    std::vector<Row> rows;    // each run's row as it will be written: a kept row, or its identity
    std::vector<bool> kept;   // by run: its earlier row stands
    std::vector<Row> carried; // --filter: the earlier rows of the plan's runs it leaves out, as they are
    std::vector<Row> samples; // the kept rows' samples, then the finished rounds of runs to time again
    // "run|config_hash" -> the rounds an interleaved sweep killed midway finished of a run with no row
    std::map<std::string, std::vector<Row>> rounds;
    std::vector<Row> earlierRows;  // every row of the earlier runs.csv (their wall_s estimate the time left)
    std::size_t setAside = 0;      // earlier rows set aside
};

// Reads the earlier runs.csv and samples.csv of `files` (an unreadable one with --force is moved
// aside whole), keeps what stands, sets aside the rest with the reasons on stderr.
Resumed resumeSweep(const ExperimentPlan& plan, const std::vector<const RunConfig*>& mine, const SweepFiles& files,
                    const RunnerOptions& options, Caches& caches);

}  // namespace rtbench
