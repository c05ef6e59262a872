// rtbench retime: a run with a (forged) timing warning is re-timed and its better-conditioned
// samples kept, with the reason, the record saved aside; the rows without a warning are left as
// they were; a re-run whose count differs from the record writes nothing; a row of another
// commit is refused.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <sstream>

#include "harness/check.h"
#include "harness/columns.h"
#include "harness/retime.h"
#include "harness/samples_check.h"
#include "harness/timing_rounds.h"
#include "core/error.h"
#include "core/input_file.h"
#include "tests/error_of.h"
#include "tests/harness/test_experiment.h"

namespace rtbench {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

// Six repetitions (the fewest with an interval) and a noise guard that never fires on its own:
// the only warning is the one a test forges.
ExperimentResult runQuietlyTimed(TempDir& dir) {
    const std::string path = dir.write("retime.toml", "[experiment]\nname = \"retime\"\noutput = \"" + dir.file("out") +
                                                          "\"\nrepetitions = 6\nwarmups = 0\nnoise_cv = 1000\nnoise_ci = 1000\nnoise_other_cpu = 1\n"
                                                          "[device]\nname = \"" + testDeviceName() + "\"\n"
                                                          "[scene]\nsource = \"procedural:christen_b\"\n"
                                                          "[camera]\nwidth = 32\nheight = 24\n[output]\nimages = false\n"
                                                          "[structure]\ntype = [\"uniform_grid\", \"bvh\"]\n");
    return runExperiment(loadExperiment(path), quietRunnerOptions());
}

std::string fileText(const std::string& path) { return readInputFile(path, kMaxResultsFileBytes, "file"); }

// Rewrites the folder's runs.csv with `edit` applied to run 001's row.
void editRun1(const std::string& folder, const std::function<void(Row&)>& edit) {
    const std::string csv = (fs::path(folder) / "runs.csv").string();
    std::vector<Row> rows = readRunsCsv(csv);
    for (Row& row : rows)
        if (row.at("run") == "001") edit(row);
    writeCsv(csv, runColumns(), rows);
}

const Row& run(const std::vector<Row>& rows, const std::string& number) {
    for (const Row& row : rows)
        if (row.at("run") == number) return row;
    throw Error("no run " + number);
}

TEST(Retime, AFlaggedRunIsRetimedItsCleanTryKeptWithTheReasonAndTheRecordSetAside) {
    TempDir dir;
    const ExperimentResult result = runQuietlyTimed(dir);
    ASSERT_EQ(result.rows.size(), 2u);
    for (const Row& row : result.rows) ASSERT_EQ(cellText(row, "timing_warning"), "") << cellText(row, "error");
    editRun1(result.folder, [](Row& row) { row["timing_warning"] = "kernel CV 0.4 > experiment.noise_cv 0.05 (forged)"; });
    const std::vector<Row> before = readRunsCsv((fs::path(result.folder) / "runs.csv").string());

    std::ostringstream out;
    const RetimeResult retimed = retimeFlagged(result.folder, RetimeOptions{2}, out);
    EXPECT_EQ(retimed.flagged, 1) << out.str();
    EXPECT_EQ(retimed.replaced, 1);
    EXPECT_EQ(retimed.cleared, 1);
    EXPECT_FALSE(retimed.failed());
    EXPECT_THAT(out.str(), HasSubstr("try 1 of 2: re-timing 1 run(s)"));
    EXPECT_THAT(out.str(), Not(HasSubstr("try 2 of 2")));  // it timed clean at once

    const std::vector<Row> after = readRunsCsv((fs::path(result.folder) / "runs.csv").string());
    ASSERT_EQ(after.size(), 2u);
    EXPECT_EQ(run(after, "000"), run(before, "000"));  // not flagged: left as it was
    const Row& fresh = run(after, "001");
    EXPECT_EQ(cellText(fresh, "timing_warning"), "");
    EXPECT_THAT(cellText(fresh, "retimed"), HasSubstr("try 1 of 2 kept (timing warning cleared"));
    EXPECT_THAT(cellText(fresh, "retimed"), HasSubstr("(forged)"));
    // columns.csv types the note as text: the scripts read it so (a number type fails them).
    EXPECT_EQ(columnValueType(columnSpec("retimed")), std::string("text"));
    EXPECT_TRUE(deterministicDifferences(run(before, "001"), fresh).empty());
    // The kept samples are the row's own (what check and compare demand).
    const std::vector<Row> samples = readSamplesCsv((fs::path(result.folder) / "samples.csv").string());
    const auto byRun = samplesByRun(samples);
    for (const Row& row : after) EXPECT_EQ(samplesProblem(row, byRun), "") << row.at("run");
    // The forged record is kept aside, with its samples.
    int aside = 0;
    for (const auto& entry : fs::directory_iterator(result.folder)) {
        const std::string name = entry.path().filename().string();
        if (name.rfind("superseded-", 0) != 0) continue;
        ++aside;
        if (name.size() > 8 && name.substr(name.size() - 8) == "runs.csv") {
            EXPECT_THAT(fileText(entry.path().string()), HasSubstr("(forged)"));
        }
    }
    EXPECT_EQ(aside, 2);
    EXPECT_THAT(fileText((fs::path(result.folder) / "context.json").string()), HasSubstr("\"runs_replaced\""));

    std::ostringstream again;
    EXPECT_EQ(retimeFlagged(result.folder, RetimeOptions{2}, again).flagged, 0);
    EXPECT_THAT(again.str(), HasSubstr("nothing to re-time"));
}

TEST(Retime, ARerunWhoseCountDiffersFromTheRecordWritesNothing) {
    TempDir dir;
    const ExperimentResult result = runQuietlyTimed(dir);
    editRun1(result.folder, [](Row& row) {
        row["timing_warning"] = "forged";
        row["hits"] = std::to_string(std::stoll(row.at("hits")) + 1);
    });
    const std::string csv = (fs::path(result.folder) / "runs.csv").string();
    const std::string recorded = fileText(csv);
    std::ostringstream out;
    const RetimeResult retimed = retimeFlagged(result.folder, RetimeOptions{1}, out);
    ASSERT_TRUE(retimed.failed());
    EXPECT_THAT(retimed.differences.front(), HasSubstr("hits"));
    EXPECT_EQ(fileText(csv), recorded);
    for (const auto& entry : fs::directory_iterator(result.folder))
        EXPECT_NE(entry.path().filename().string().rfind("superseded-", 0), 0u) << entry.path();
}

TEST(Retime, ARowOfAnotherCommitIsRefusedByName) {
    TempDir dir;
    const ExperimentResult result = runQuietlyTimed(dir);
    editRun1(result.folder, [](Row& row) {
        row["timing_warning"] = "forged";
        row["git_commit"] = "0000000";
    });
    std::ostringstream out;
    const std::string error = errorOf([&] { retimeFlagged(result.folder, RetimeOptions{1}, out); });
    EXPECT_THAT(error, HasSubstr("run 001 was timed by commit 0000000"));
    EXPECT_THAT(errorOf([&] { retimeFlagged(result.folder, RetimeOptions{0}, out); }), HasSubstr("--tries 0"));
}

}  // namespace
}  // namespace rtbench
