// rtbench compare on two synthetic result sets made from one real run: an injected 20% slowdown
// is SLOWER, noise alone SAME, a flagged run UNSURE, fifteen runs of noise no SLOWER after Holm,
// machine drift SAME against Embree, a count difference a count, no match exit 2 naming the key
// that differs, and what one side lacks (runs, samples, columns) is named.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

#include "harness/compare.h"
#include "harness/config.h"
#include "harness/statistics.h"
#include "harness/runner.h"
#include "harness/timing_rounds.h"
#include "core/error.h"
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
        rows_ = readCsv(a_ + "/runs.csv");
        for (Row& row : rows_) row["timing_warning"] = "";  // one repetition: the samples below stand in
        writeCsv(a_ + "/runs.csv", runColumns(), rows_);
        fs::copy(a_, b_);
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
        writeBoth(a, b);
    }
    // A folder's rows as its samples make them (what the runner writes): each method's median of
    // its samples, timing_repetitions their count, no Embree 16 where it has none.
    static void matchRowsToSamples(const std::string& folder) {
        std::vector<Row> rows = readCsv(folder + "/runs.csv");
        const std::vector<Row> samples = readCsv(folder + "/samples.csv");
        for (Row& row : rows) {
            for (const char* method : {"kernel", "embree1", "embree16"}) {
                std::vector<double> ms;
                for (const Row& s : samples)
                    if (s.at("run") == row.at("run") && s.at("method") == method) ms.push_back(std::stod(s.at("ms")));
                row[std::string(method) + "_ms_median"] = ms.empty() ? "" : formatNumber(median(ms));
                if (std::string(method) == "kernel") row["timing_repetitions"] = std::to_string(ms.size());
            }
        }
        writeCsv(folder + "/runs.csv", runColumns(), rows);
    }
    void writeBoth(const std::vector<Row>& a, const std::vector<Row>& b) const {
        writeCsv(a_ + "/samples.csv", sampleColumns(), a);
        writeCsv(b_ + "/samples.csv", sampleColumns(), b);
        matchRowsToSamples(a_);
        matchRowsToSamples(b_);
    }
    CompareResult compare(const CompareOptions& options = {}) const { return compareFolders(a_, b_, options); }
    TempDir dir_;
    std::string a_, b_;
    std::vector<Row> rows_;
};

TEST_F(Compare, AnInjectedSlowdownIsSlowerAndNoiseAloneIsSame) {
    ASSERT_EQ(rows_.size(), 3u);
    writeSamples(0.2);
    const CompareResult r = compare();
    ASSERT_EQ(r.runs.size(), 3u);
    EXPECT_EQ(r.runs[0].verdict, Verdict::Slower);
    EXPECT_NEAR(r.runs[0].change, 0.2, 0.01);
    EXPECT_LT(r.runs[0].p, 0.001);  // ten against ten, fully separated
    EXPECT_NEAR(r.runs[0].pHolm, 3 * r.runs[0].p, 1e-12) << "the smallest of three p-values, times three";
    EXPECT_LE(r.runs[0].changeLow, r.runs[0].change);
    EXPECT_GE(r.runs[0].changeHigh, r.runs[0].change);
    for (std::size_t i = 1; i < 3; ++i) {
        EXPECT_EQ(r.runs[i].verdict, Verdict::Same) << i;
        EXPECT_LT(std::abs(r.runs[i].change), 0.01) << i;
    }
    EXPECT_EQ(r.slower, 1);
    EXPECT_EQ(r.same, 2);
    EXPECT_EQ(r.countDifferences, 0);
    EXPECT_EQ(r.exitStatus(), 1);
    std::ostringstream out;
    printComparison(r, a_, b_, {}, out);
    EXPECT_THAT(out.str(), HasSubstr("SLOWER"));
    EXPECT_THAT(out.str(), HasSubstr("2 SAME, 0 FASTER, 1 SLOWER, 0 UNSURE"));

    // A 3% slowdown is significant but within the threshold: SAME; a 20% speed-up is FASTER.
    writeSamples(0.03);
    EXPECT_EQ(compare().runs[0].verdict, Verdict::Same);
    EXPECT_EQ(compare().exitStatus(), 0);
    writeSamples(-0.2);
    const CompareResult faster = compare();
    EXPECT_EQ(faster.runs[0].verdict, Verdict::Faster);
    EXPECT_EQ(faster.exitStatus(), 0);
}

// A run with a timing warning on either side is UNSURE, whatever its samples say, and never fails.
TEST_F(Compare, AFlaggedRunIsUnsure) {
    writeSamples(0.2);
    std::vector<Row> rows = readCsv(b_ + "/runs.csv");  // as its samples made them
    rows[0]["timing_warning"] = "kernel CV 0.2 > experiment.noise_cv 0.05";
    writeCsv(b_ + "/runs.csv", runColumns(), rows);
    const CompareResult r = compare();
    EXPECT_EQ(r.runs[0].verdict, Verdict::Unsure);
    EXPECT_EQ(r.runs[0].why, "timing warning in B");
    EXPECT_EQ(r.slower, 0);
    EXPECT_EQ(r.exitStatus(), 0);
}

// A median 10% slower is no slowdown when the samples do not say so: B's 8, 8, 8, 8, 11, 11, 14,
// 14, 14, 14 against A's ten near 10 (U = 60 of 100, p = 0.47): UNSURE.
TEST_F(Compare, ALargeChangeWithoutEvidenceIsUnsure) {
    std::vector<Row> a, b;
    for (const Row& row : rows_) {
        addSamples(a, row, "kernel", 10.0, 1.0);
        for (int i = 0; i < 10; ++i)
            b.push_back({{"run", row.at("run")}, {"config_hash", row.at("config_hash")}, {"method", "kernel"},
                         {"round", std::to_string(i)}, {"repetition", std::to_string(i)},
                         {"ms", i < 4 ? "8" : i < 6 ? "11" : "14"}, {"t_s", std::to_string(i)}});
    }
    writeBoth(a, b);
    const CompareResult r = compare();
    ASSERT_EQ(r.runs.size(), 3u);
    EXPECT_GT(r.runs[0].change, 0.05);
    EXPECT_GT(r.runs[0].p, 0.05);
    EXPECT_EQ(r.runs[0].verdict, Verdict::Unsure);
    EXPECT_EQ(r.exitStatus(), 0);
}

// Fifteen runs, five samples a side: B's five above A's five in one run (8% slower, p = 2/252 =
// 0.0079, the smallest five against five can give) is significant alone but not after Holm's
// correction for fifteen (0.119): UNSURE, no SLOWER.
TEST_F(Compare, FifteenRunsOfNoiseGiveNoSlowerAfterHolm) {
    std::vector<Row> rowsA, rowsB, a, b;
    for (int i = 0; i < 15; ++i) {
        Row row = rows_[0];
        row["run"] = (i < 10 ? "00" : "0") + std::to_string(i);
        row["structure_min_dim"] = std::to_string(100 + i);
        row["config_hash"] = "hash" + std::to_string(i);
        rowsA.push_back(row);
        for (int k = 0; k < 5; ++k) {
            auto sample = [&](double ms) {
                return Row{{"run", row.at("run")}, {"config_hash", row.at("config_hash")}, {"method", "kernel"},
                           {"round", std::to_string(k)}, {"repetition", std::to_string(k)}, {"ms", formatNumber(ms, 9)},
                           {"t_s", std::to_string(k)}};
            };
            a.push_back(sample(10.0 + 0.1 * k));
            b.push_back(sample(i == 0 ? 10.8 + 0.1 * k : 10.0 + 0.1 * ((k + i) % 5)));
        }
    }
    writeCsv(a_ + "/runs.csv", runColumns(), rowsA);
    writeCsv(b_ + "/runs.csv", runColumns(), rowsA);
    writeBoth(a, b);
    const CompareResult r = compare();
    ASSERT_EQ(r.runs.size(), 15u);
    EXPECT_NEAR(r.runs[0].p, 2.0 / 252.0, 1e-12);
    EXPECT_NEAR(r.runs[0].pHolm, 15 * 2.0 / 252.0, 1e-12);
    EXPECT_EQ(r.runs[0].verdict, Verdict::Unsure);
    EXPECT_EQ(r.slower, 0);
    EXPECT_EQ(r.unsure, 1);
    EXPECT_EQ(r.same, 14);
    EXPECT_EQ(r.exitStatus(), 0);
}

// The machine 20% slower as a whole (kernel and Embree alike): SLOWER on the kernel's time, SAME
// against Embree on the same rays.
TEST_F(Compare, MachineDriftIsSameRelativeToEmbree) {
    std::vector<Row> a, b;
    for (const Row& row : rows_) {
        addSamples(a, row, "kernel", 10.0, 1.0);
        addSamples(b, row, "kernel", 10.0, 1.2, 3);
        addSamples(a, row, "embree1", 2.0, 1.0);
        addSamples(b, row, "embree1", 2.0, 1.2, 5);
    }
    writeBoth(a, b);
    EXPECT_EQ(compare().slower, 3);
    const CompareResult relative = compare({.relativeTo = "embree1"});
    EXPECT_EQ(relative.same, 3);
    EXPECT_EQ(relative.exitStatus(), 0);
    EXPECT_NEAR(relative.runs[0].medianA, 10.0 * 1.0045 / (2.0 * 1.0045), 0.01) << "kernel ms / Embree's median";
    EXPECT_THROW(compare({.relativeTo = "embree16x"}), Error);
}

// Host-controlled multipass's kernel_ms is its live loop from results schema 25 on, its replayed
// passes before: across that line the two are different measures, UNSURE with the reason, never
// SLOWER (the live loop is the longer); multipass with the oracle on the device is compared. A row
// of a schema before strategy.control (empty cell) ran the key's default, the host.
TEST_F(Compare, HostMultipassAcrossResultsSchema25IsUnsure) {
    writeSamples(0.2);
    for (const std::string& folder : {a_, b_}) {
        std::vector<Row> rows = readCsv(folder + "/runs.csv");
        for (std::size_t i = 0; i < rows.size(); ++i) {
            rows[i]["strategy_type"] = "multipass";
            rows[i]["strategy_control"] = i == 0 ? "host" : i == 1 ? "device" : "";
        }
        std::vector<std::string> columns = runColumns();
        if (folder == a_)  // A as results schema 24 wrote it: no column of a later schema (kernel_ms_replay, ...)
            for (const ColumnSpec& c : runColumnSpecs())
                if (c.since > 24) {
                    std::erase(columns, c.name);
                    for (Row& row : rows) row.erase(c.name);
                }
        writeCsv(folder + "/runs.csv", columns, rows);
    }
    CompareResult r = compare();
    EXPECT_EQ(r.runs[0].verdict, Verdict::Unsure);
    EXPECT_THAT(r.runs[0].why, HasSubstr("A: schema 24, B: " + std::to_string(kSchemaVersion)));
    EXPECT_EQ(r.slower, 0);
    EXPECT_EQ(r.runs[1].verdict, Verdict::Same) << "the oracle on the device: kernel_ms measured alike";
    EXPECT_EQ(r.runs[2].verdict, Verdict::Unsure) << "no strategy.control: the host's";
    writeCsv(a_ + "/runs.csv", runColumns(), readCsv(a_ + "/runs.csv"));  // both of today's schema
    r = compare();
    EXPECT_EQ(r.runs[0].verdict, Verdict::Slower);
}

// No run matches when the folders differ in a key: exit 2, the key named; --ignore matches across it.
TEST_F(Compare, NoMatchIsExitTwoNamingTheKeyAndIgnoreMatches) {
    writeSamples(0.0);
    std::vector<Row> rows = readCsv(b_ + "/runs.csv");  // as its samples made them
    for (Row& row : rows) row["intersection_test"] = "watertight";
    writeCsv(b_ + "/runs.csv", runColumns(), rows);
    const CompareResult r = compare();
    EXPECT_TRUE(r.runs.empty());
    EXPECT_EQ(r.onlyA.size(), 3u);
    EXPECT_EQ(r.exitStatus(), 2);
    EXPECT_THAT(r.differingKeys, ::testing::ElementsAre("intersection.test: A moller_trumbore; B watertight"));
    std::ostringstream out;
    printComparison(r, a_, b_, {}, out);
    EXPECT_THAT(out.str(), HasSubstr("no run matched: nothing compared (--ignore KEY matches runs across a key)"));
    const CompareResult ignored = compare({.ignore = {"intersection.test"}});
    EXPECT_EQ(ignored.runs.size(), 3u);
    EXPECT_EQ(ignored.exitStatus(), 0);
    EXPECT_THROW(compare({.ignore = {"intersection.tset"}}), Error);
}

TEST_F(Compare, ACountDifferenceIsReportedAsACount) {
    writeSamples(0.0);
    std::vector<Row> rows = readCsv(b_ + "/runs.csv");  // as its samples made them
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

// The samples are the evidence: a folder of results schema 5 on whose samples are missing, forged
// or of another config is refused, naming the file, the run and what is wrong (the rows' medians x
// 50 with samples.csv deleted used to pass as "no test").
TEST_F(Compare, SamplesThatAreNotTheRowsAreRefused) {
    auto refusal = [&]() -> std::string {
        try {
            compare();
        } catch (const Error& e) {
            return e.what();
        }
        return "accepted";
    };
    writeSamples(0.0);
    const std::vector<Row> rows = readCsv(b_ + "/runs.csv");
    const std::vector<Row> samples = readCsv(b_ + "/samples.csv");
    fs::remove(b_ + "/samples.csv");
    EXPECT_THAT(refusal(), HasSubstr("samples.csv: missing; a folder of results schema"));

    std::vector<Row> forged = rows;
    forged[1]["kernel_ms_median"] = formatNumber(50 * std::stod(rows[1].at("kernel_ms_median")));
    writeCsv(b_ + "/samples.csv", sampleColumns(), samples);
    writeCsv(b_ + "/runs.csv", runColumns(), forged);
    EXPECT_THAT(refusal(), HasSubstr("run 001 (structure.min_dim=6): the kernel samples' median"));
    writeCsv(b_ + "/runs.csv", runColumns(), rows);
    EXPECT_EQ(refusal(), "accepted");

    std::vector<Row> negative = samples;
    negative[0]["ms"] = "-5";
    writeCsv(b_ + "/samples.csv", sampleColumns(), negative);
    EXPECT_THAT(refusal(), HasSubstr("sample '-5' is not a positive number of ms"));

    std::vector<Row> twice = samples;
    twice.push_back(samples[0]);
    writeCsv(b_ + "/samples.csv", sampleColumns(), twice);
    EXPECT_THAT(refusal(), HasSubstr("round 0 repetition 0 twice"));

    std::vector<Row> otherConfig = samples;
    for (Row& sample : otherConfig)
        if (sample.at("run") == "002") sample["config_hash"] = "0123456789abcdef";
    writeCsv(b_ + "/samples.csv", sampleColumns(), otherConfig);
    EXPECT_THAT(refusal(), HasSubstr("run 002 (structure.min_dim=8): no samples of its run and config hash"));
}

TEST_F(Compare, WhatOneSideLacksIsNamed) {
    writeSamples(0.2);
    // A run only in A, and a B of an older schema: no samples, fewer columns.
    std::vector<Row> rows = readCsv(b_ + "/runs.csv");  // as its samples made them
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
    EXPECT_EQ(r.runs[0].verdict, Verdict::Unsure);
    EXPECT_LT(r.runs[0].p, 0.0);
    EXPECT_THAT(r.runs[0].why, HasSubstr("no samples of this run in B"));
    EXPECT_EQ(r.exitStatus(), 0);
}

}  // namespace
}  // namespace rtbench
