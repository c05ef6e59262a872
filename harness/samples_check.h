// A row's timing samples (samples.csv) are its own: the evidence compare tests, resume keeps and
// check re-reads. Each ok row of results schema 5 on must have, for every method it reports a
// median of (kernel, embree1, embree16), timing_repetitions samples of its run and config hash,
// each a positive number of ms, no (method, round, repetition) twice, whose median is the row's;
// with experiment.build_rounds, build_rounds samples of structure_build and embree_build alike.
#pragma once
#include <map>
#include <string>
#include <vector>

#include "schema/columns.h"

namespace rtbench {

// A run's key across runs.csv and samples.csv rows: "run|config_hash".
std::string runKey(const Row& row);

// samples.csv rows grouped by runKey.
std::map<std::string, std::vector<const Row*>> samplesByRun(const std::vector<Row>& samples);

// Why `row`'s samples are not its own, "" when they are (or the row has no timing to back: a
// failed run, a folder before results schema 5).
std::string samplesProblem(const Row& row, const std::map<std::string, std::vector<const Row*>>& byRun);

}  // namespace rtbench
