// rtbench compare on two synthetic result sets made from one real run: an injected 20% slowdown
// is flagged, noise alone is not, a count difference is reported as a count, and what one side
// lacks (runs, samples, columns) is named.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

#include "harness/compare.h"
#include "harness/config.h"
#include "harness/runner.h"
#include "harness/timing_rounds.h"
#include "tests/device/test_device.h"
#include "tests/temp_dir.h"

namespace rtbench {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;

class Compare : public ::testing::Test {
protected:
    void SetUp() override {
        const std::string path = dir_.write(
            "c.toml", "[experiment]\nname = \"a\"\noutput = \"" + dir_.file("out") + "\"\nrepetitions = 1\nwarmups = 0\n[device]\nname = \"" +
                          testDeviceName() +
                          "\"\n[scene]\nsource = \"procedural:christen_a\"\n[camera]\nwidth = 16\nheight = 16\n[structure]\n"
                          "min_dim = [4, 6, 8]\n[output]\nimages = false\n");
        RunnerOptions quiet;
        quiet.quiet = true;
        a_ = runExperiment(loadExperiment(path), quiet).folder;
        b_ = dir_.file("b");
        fs::copy(a_, b_);
        rows_ = readCsv(a_ + "/runs.csv");
    }
    // Ten samples per method: `base` ms times (1 + 0.1% * a fixed pattern), scaled by `scale`.
    static void addSamples(std::vector<Row>& samples, const Row& row, const std::string& method, double base, double scale,
                           int shift = 0) {
        for (int i = 0; i < 10; ++i)
            samples.push_back({{"run", row.at("run")}, {"config_hash", row.at("config_hash")}, {"method", method},
                               {"round", std::to_string(i)}, {"repetition", std::to_string(i)},
                               {"ms", formatNumber(base * scale * (1.0 + 0.001 * ((i * 7 + shift) % 10)), 9)},
                               {"t_s", std::to_string(i)}});
    }
    // Both folders' samples: run 000 of B 20% slower, the others B's own noise of the same size.
    void writeSamples(double slowdown) {
        std::vector<Row> a, b;
        for (const Row& row : rows_) {
            const bool first = row.at("run") == "000";
            addSamples(a, row, "kernel", 10.0, 1.0);
            addSamples(b, row, "kernel", 10.0, first ? 1.0 + slowdown : 1.0, 3);
            addSamples(a, row, "embree1", 2.0, 1.0);
            addSamples(b, row, "embree1", 2.0, 1.0, 5);
        }
        writeCsv(a_ + "/samples.csv", sampleColumns(), a);
        writeCsv(b_ + "/samples.csv", sampleColumns(), b);
    }
    CompareResult compare() const { return compareFolders(a_, b_, {}); }
    TempDir dir_;
    std::string a_, b_;
    std::vector<Row> rows_;
};

TEST_F(Compare, AnInjectedSlowdownIsFlaggedAndNoiseAloneIsNot) {
    ASSERT_EQ(rows_.size(), 3u);
    writeSamples(0.2);
    const CompareResult r = compare();
    ASSERT_EQ(r.runs.size(), 3u);
    EXPECT_TRUE(r.runs[0].regression);
    EXPECT_NEAR(r.runs[0].change, 0.2, 0.01);
    EXPECT_LT(r.runs[0].p, 0.001);  // ten against ten, fully separated
    EXPECT_LE(r.runs[0].changeLow, r.runs[0].change);
    EXPECT_GE(r.runs[0].changeHigh, r.runs[0].change);
    for (std::size_t i = 1; i < 3; ++i) {
        EXPECT_FALSE(r.runs[i].regression) << i;
        EXPECT_LT(std::abs(r.runs[i].change), 0.01) << i;
        EXPECT_GT(r.runs[i].p, 0.05) << i;
    }
    EXPECT_EQ(r.regressions, 1);
    EXPECT_EQ(r.countDifferences, 0);
    EXPECT_EQ(r.exitStatus(), 1);
    std::ostringstream out;
    printComparison(r, a_, b_, {}, out);
    EXPECT_THAT(out.str(), HasSubstr("SLOWER"));
    EXPECT_THAT(out.str(), HasSubstr("1 significantly slower beyond 5.0%"));

    // A 3% slowdown is significant but within the threshold; a 20% speed-up is "faster".
    writeSamples(0.03);
    EXPECT_EQ(compare().exitStatus(), 0);
    writeSamples(-0.2);
    const CompareResult faster = compare();
    EXPECT_TRUE(faster.runs[0].improvement);
    EXPECT_EQ(faster.exitStatus(), 0);
}

// A median 10% slower is no slowdown when the samples do not say so: B's 8, 8, 8, 8, 11, 11, 14,
// 14, 14, 14 against A's ten near 10 (U = 60 of 100, p = 0.47).
TEST_F(Compare, ALargeChangeWithoutEvidenceIsNotFlagged) {
    std::vector<Row> a, b;
    for (const Row& row : rows_) {
        addSamples(a, row, "kernel", 10.0, 1.0);
        for (int i = 0; i < 10; ++i)
            b.push_back({{"run", row.at("run")}, {"config_hash", row.at("config_hash")}, {"method", "kernel"},
                         {"round", std::to_string(i)}, {"repetition", std::to_string(i)},
                         {"ms", i < 4 ? "8" : i < 6 ? "11" : "14"}, {"t_s", std::to_string(i)}});
    }
    writeCsv(a_ + "/samples.csv", sampleColumns(), a);
    writeCsv(b_ + "/samples.csv", sampleColumns(), b);
    const CompareResult r = compare();
    ASSERT_EQ(r.runs.size(), 3u);
    EXPECT_GT(r.runs[0].change, 0.05);
    EXPECT_GT(r.runs[0].p, 0.05);
    EXPECT_FALSE(r.runs[0].regression);
    EXPECT_EQ(r.exitStatus(), 0);
}

TEST_F(Compare, ACountDifferenceIsReportedAsACount) {
    writeSamples(0.0);
    std::vector<Row> rows = rows_;
    const std::string hits = rows[2].at("hits");
    rows[2]["hits"] = std::to_string(std::stoull(hits) + 1);
    writeCsv(b_ + "/runs.csv", runColumns(), rows);
    const CompareResult r = compare();
    EXPECT_EQ(r.countDifferences, 1);
    ASSERT_EQ(r.runs[2].countDifferences.size(), 1u);
    EXPECT_EQ(r.runs[2].countDifferences[0], "hits: " + hits + " -> " + std::to_string(std::stoull(hits) + 1));
    EXPECT_EQ(r.exitStatus(), 1);
    std::ostringstream out;
    printComparison(r, a_, b_, {.markdown = true}, out);
    EXPECT_THAT(out.str(), HasSubstr("count differs: run 002 -> 002"));
    EXPECT_THAT(out.str(), HasSubstr("| A | B | parameters |"));
}

TEST_F(Compare, WhatOneSideLacksIsNamed) {
    writeSamples(0.2);
    // A run only in A, and a B of an older schema: no samples, fewer columns.
    std::vector<Row> rows = rows_;
    rows.erase(rows.begin() + 1);
    std::vector<std::string> columns;
    for (const ColumnSpec& c : runColumnSpecs())
        if (c.since < 5) columns.push_back(c.name);
    for (Row& row : rows)
        for (const ColumnSpec& c : runColumnSpecs())
            if (c.since >= 5) row.erase(c.name);
    writeCsv(b_ + "/runs.csv", columns, rows);
    fs::remove(b_ + "/samples.csv");
    const CompareResult r = compare();
    ASSERT_EQ(r.onlyA.size(), 1u);
    EXPECT_THAT(r.onlyA[0], HasSubstr("001"));
    EXPECT_TRUE(r.onlyB.empty());
    EXPECT_THAT(r.columnsOnlyA, ::testing::Contains("kernel_ms_ci_low"));
    ASSERT_EQ(r.runs.size(), 2u);
    // Medians only: the 20% slowdown is shown, but not judged without samples.
    EXPECT_FALSE(r.runs[0].regression);
    EXPECT_LT(r.runs[0].p, 0.0);
    EXPECT_THAT(r.runs[0].note, HasSubstr("no samples of this run in B"));
    EXPECT_EQ(r.exitStatus(), 0);
}

}  // namespace
}  // namespace rtbench
