// experiment.build_rounds (issue 47 §2): the structure's build and Embree's BVH build of the same
// triangles timed alternately, round after round, as the kernels are timed against Embree's
// traversal (harness/timing_rounds.h), so that the machine's drift hits both builds alike; their
// medians, and their ratio with an interval that holds at the sample size.
#pragma once
#include <functional>
#include <vector>

#include "schema/columns.h"
#include "timing_rounds.h"

namespace rtbench {

struct BuildRounds {
    std::vector<double> structureMs, embreeMs;  // one of each per round
};

// Round r times buildStructure then buildEmbree when r is even, the other way round when odd;
// each returns its own build time in ms.
BuildRounds timeBuildRounds(int rounds, const std::function<double()>& buildStructure, const std::function<double()>& buildEmbree);

// The rounds as samples.csv holds them: methods structure_build and embree_build, repetition =
// round, t = `secondsAtStart` (when the rounds began, on the samples' clock) for every one.
std::vector<TimingSample> buildRoundSamples(const BuildRounds& rounds, double secondsAtStart);

// The columns timeBuildRounds' results go to (empty when experiment.build_rounds = 0), and writing them.
const std::vector<ColumnSpec>& buildRoundColumns();
void writeBuildRoundColumns(const BuildRounds& rounds, Row& row);

}  // namespace rtbench
