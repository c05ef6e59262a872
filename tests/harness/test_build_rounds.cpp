// experiment.build_rounds (harness/build_rounds.h): the two builds alternate who goes first, the
// row's medians, ratio and interval follow from the samples by hand, samples.csv holds every
// round, and samples_check.h refuses a row its build samples do not back.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "harness/build_rounds.h"
#include "harness/samples_check.h"
#include "harness/writers.h"
#include "tests/harness/test_experiment.h"

namespace rtbench {
namespace {

TEST(BuildRounds, AlternateWhichBuildGoesFirst) {
    std::string order;
    double structure = 10.0, embree = 1.0;
    const BuildRounds b = timeBuildRounds(
        4, [&] { order += 'S'; return structure++; }, [&] { order += 'E'; return embree++; });
    EXPECT_EQ(order, "SEESSEES");
    EXPECT_EQ(b.structureMs, (std::vector<double>{10, 11, 12, 13}));
    EXPECT_EQ(b.embreeMs, (std::vector<double>{1, 2, 3, 4}));
    EXPECT_TRUE(timeBuildRounds(0, [] { return 1.0; }, [] { return 1.0; }).structureMs.empty());
}

// Seven rounds: medians 13 and 7; each median's 97.5% interval is [min, max] (coverage 1 - 2 /
// 128 = 98.4%; [x(2), x(6)] covers 1 - 2 * 8/128 = 87.5%), so the ratio's is [10 / 10, 16 / 4].
TEST(BuildRounds, RowHoldsTheMediansTheirRatioAndItsInterval) {
    const BuildRounds b{{16, 10, 13, 11, 15, 12, 14}, {4, 10, 7, 5, 9, 6, 8}};
    Row row;
    writeBuildRoundColumns(b, row);
    EXPECT_EQ(row.at("build_rounds"), "7");
    EXPECT_EQ(row.at("structure_build_ms_median"), "13");
    EXPECT_EQ(row.at("embree_build_ms_median"), "7");
    EXPECT_EQ(row.at("build_ratio_vs_embree"), "1.857");
    EXPECT_EQ(row.at("build_ratio_ci_low"), "1");
    EXPECT_EQ(row.at("build_ratio_ci_high"), "4");
    // Six rounds are too few for the interval; no rounds write their count alone.
    Row six, none;
    writeBuildRoundColumns({{1, 2, 3, 4, 5, 6}, {1, 2, 3, 4, 5, 6}}, six);
    EXPECT_EQ(six.at("build_ratio_vs_embree"), "1");
    EXPECT_EQ(six.count("build_ratio_ci_low"), 0u);
    writeBuildRoundColumns({}, none);
    EXPECT_EQ(none, (Row{{"build_rounds", "0"}}));
}

// A whole run: its build rounds in the row and in samples.csv, which back it; a row whose median
// or count its samples do not give is refused.
TEST(BuildRounds, ARunRecordsEveryRoundAndItsSamplesBackTheRow) {
    TempDir dir;
    const std::string path = dir.write("build_rounds.toml", "[experiment]\nname = \"build_rounds\"\noutput = \"" + dir.file("out") +
                                                                "\"\nrepetitions = 1\nwarmups = 0\nbuild_rounds = 7\n[device]\nname = \"" +
                                                                testDeviceName() + "\"\n[camera]\nwidth = 8\nheight = 8\n[scene]\n"
                                                                "source = \"procedural:christen_b\"\n[structure]\ntype = \"uniform_grid\"\nmin_dim = 8\n");
    const ExperimentResult result = runExperiment(loadExperiment(path), quietRunnerOptions());
    ASSERT_EQ(result.rows.size(), 1u);
    Row row = result.rows[0];
    ASSERT_EQ(row.at("status"), "ok") << row.at("error");
    EXPECT_EQ(row.at("build_rounds"), "7");
    const std::vector<Row> samples = readCsv(result.folder + "/samples.csv");
    std::vector<double> structure, embree;
    for (const Row& s : samples) {
        if (s.at("method") == "structure_build") structure.push_back(std::stod(s.at("ms")));
        if (s.at("method") == "embree_build") embree.push_back(std::stod(s.at("ms")));
    }
    ASSERT_EQ(structure.size(), 7u);
    ASSERT_EQ(embree.size(), 7u);
    EXPECT_NEAR(std::stod(row.at("build_ratio_vs_embree")),
                std::stod(row.at("structure_build_ms_median")) / std::stod(row.at("embree_build_ms_median")), 1e-3 * std::stod(row.at("build_ratio_vs_embree")));
    EXPECT_FALSE(row.at("build_ratio_ci_low").empty());
    const auto byRun = samplesByRun(samples);
    EXPECT_EQ(samplesProblem(row, byRun), "");
    Row moved = row;
    moved["structure_build_ms_median"] = formatNumber(std::stod(row.at("structure_build_ms_median")) * 1.01);
    EXPECT_NE(samplesProblem(moved, byRun).find("structure_build samples' median"), std::string::npos) << samplesProblem(moved, byRun);
    Row more = row;
    more["build_rounds"] = "8";
    EXPECT_EQ(samplesProblem(more, byRun), "7 structure_build samples, build_rounds says 8");
}

}  // namespace
}  // namespace rtbench
