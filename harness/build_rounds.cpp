#include "build_rounds.h"

#include "schema/column.h"
#include "statistics.h"

namespace rtbench {

BuildRounds timeBuildRounds(int rounds, const std::function<double()>& buildStructure, const std::function<double()>& buildEmbree) {
    BuildRounds b;
    for (int r = 0; r < rounds; ++r) {
        if (r % 2 == 0) b.structureMs.push_back(buildStructure());
        b.embreeMs.push_back(buildEmbree());
        if (r % 2 == 1) b.structureMs.push_back(buildStructure());
    }
    return b;
}

std::vector<TimingSample> buildRoundSamples(const BuildRounds& rounds, double secondsAtStart) {
    std::vector<TimingSample> samples;
    for (int r = 0; r < int(rounds.structureMs.size()); ++r) {
        samples.push_back({"structure_build", r, r, rounds.structureMs[r], secondsAtStart});
        samples.push_back({"embree_build", r, r, rounds.embreeMs[r], secondsAtStart});
    }
    return samples;
}

namespace {

// experiment.build_rounds (results schema 27), declared once, here, where its values are written.
struct BuildRoundColumns {
    using K = ColumnKind;
    ColumnGroup group;
    Column<std::uint64_t> rounds = group.add<std::uint64_t>(
        {"build_rounds", K::Timing, "rounds", "experiment.build_rounds: rounds in which the structure and Embree's BVH were built again, alternately, for the columns below (0: not timed so)", 0.0, false, {}, 27});
    // 6 digits, as samples_check.h reads them.
    Column<double> structureMedian = group.add<double>(
        {"structure_build_ms_median", K::Timing, "ms", "structure_build_ms, median over the build rounds (samples.csv: method structure_build): each round builds it as the run does and times what structure_build_ms times (the CPU build; the driver's: its build on the device)", 0.0, false, {}, 27});
    Column<double> embreeMedian = group.add<double>(
        {"embree_build_ms_median", K::Timing, "ms", "embree_build_ms, median over the build rounds (samples.csv: method embree_build) (the same triangles, a new scene on the run's Embree device)", 0.0, false, {}, 27});
    Column<double> ratio = group.add<double>(
        {"build_ratio_vs_embree", K::Timing, "ratio", "structure_build_ms_median / embree_build_ms_median: above 1, the structure takes longer to build", 0.0, false, {}, 27}, 4);
    Column<double> ratioLow = group.add<double>(
        {"build_ratio_ci_low", K::Timing, "ratio", "build_ratio_vs_embree: 95% interval from each median's 97.5% order-statistic interval (both hold at once with at least 95%; empty below 7 rounds), low end", 0.0, false, {}, 27}, 4);
    Column<double> ratioHigh = group.add<double>(
        {"build_ratio_ci_high", K::Timing, "ratio", "build_ratio_vs_embree: 95% interval (as _ci_low), high end", 0.0, false, {}, 27}, 4);
};

const BuildRoundColumns& buildRoundColumnsDeclared() {
    static const BuildRoundColumns columns;
    return columns;
}

}  // namespace

const std::vector<ColumnSpec>& buildRoundColumns() { return buildRoundColumnsDeclared().group.specs(); }

void writeBuildRoundColumns(const BuildRounds& rounds, Row& row) {
    const BuildRoundColumns& c = buildRoundColumnsDeclared();
    put(row, c.rounds, rounds.structureMs.size());
    if (rounds.structureMs.empty()) return;
    const double structure = median(rounds.structureMs), embree = median(rounds.embreeMs);
    put(row, c.structureMedian, structure);
    put(row, c.embreeMedian, embree);
    put(row, c.ratio, structure / embree);
    if (const auto ci = ratioOfMediansInterval(rounds.structureMs, rounds.embreeMs)) {
        put(row, c.ratioLow, ci->low);
        put(row, c.ratioHigh, ci->high);
    }
}

}  // namespace rtbench
