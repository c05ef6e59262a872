#include "build_rounds.h"

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

const std::vector<ColumnSpec>& buildRoundColumns() {
    using K = ColumnKind;
    static const std::vector<ColumnSpec> columns = [] {
        std::vector<ColumnSpec> c{
            {"build_rounds", K::Timing, "rounds", "experiment.build_rounds: rounds in which the structure and Embree's BVH were built again, alternately, for the columns below (0: not timed so)"},
            {"structure_build_ms_median", K::Timing, "ms", "structure_build_ms, median over the build rounds (samples.csv: method structure_build): each round builds it as the run does and times what structure_build_ms times (the CPU build; the driver's: its build on the device)"},
            {"embree_build_ms_median", K::Timing, "ms", "embree_build_ms, median over the build rounds (samples.csv: method embree_build) (the same triangles, a new scene on the run's Embree device)"},
            {"build_ratio_vs_embree", K::Timing, "ratio", "structure_build_ms_median / embree_build_ms_median: above 1, the structure takes longer to build"},
            {"build_ratio_ci_low", K::Timing, "ratio", "build_ratio_vs_embree: 95% interval from each median's 97.5% order-statistic interval (both hold at once with at least 95%; empty below 7 rounds), low end"},
            {"build_ratio_ci_high", K::Timing, "ratio", "build_ratio_vs_embree: 95% interval (as _ci_low), high end"},
        };
        for (ColumnSpec& s : c) s.since = 27;
        return c;
    }();
    return columns;
}

void writeBuildRoundColumns(const BuildRounds& rounds, Row& row) {
    row["build_rounds"] = std::to_string(rounds.structureMs.size());
    if (rounds.structureMs.empty()) return;
    const double structure = median(rounds.structureMs), embree = median(rounds.embreeMs);
    row["structure_build_ms_median"] = formatNumber(structure);  // 6 digits, as samples_check.h reads them
    row["embree_build_ms_median"] = formatNumber(embree);
    row["build_ratio_vs_embree"] = formatNumber(structure / embree, 4);
    if (const auto ci = ratioOfMediansInterval(rounds.structureMs, rounds.embreeMs)) {
        row["build_ratio_ci_low"] = formatNumber(ci->low, 4);
        row["build_ratio_ci_high"] = formatNumber(ci->high, 4);
    }
}

}  // namespace rtbench
