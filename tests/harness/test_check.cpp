// rtbench check: a deliberately changed count in a golden folder must fail, with the difference named.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

#include "harness/check.h"
#include "harness/runner.h"
#include "tests/temp_dir.h"

namespace rtbench {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;

TEST(Check, TimingColumnsAreToldApartFromCounts) {
    EXPECT_TRUE(isTimingColumn("kernel_ms_median"));
    EXPECT_TRUE(isTimingColumn("embree16_mrays_s"));
    EXPECT_TRUE(isTimingColumn("grid_build_ms"));
    EXPECT_FALSE(isTimingColumn("passes_total"));
    EXPECT_FALSE(isTimingColumn("bytes_stencil"));
    EXPECT_FALSE(isTimingColumn("hit_miss_agreement"));
}

TEST(Check, TheGoldenFolderReproducesAndAChangedCountFails) {
    TempDir dir;
    const fs::path golden = fs::path(RTBENCH_SOURCE_DIR) / "results" / "golden";
    const fs::path copy = dir.path() / "golden";
    fs::copy(golden, copy);
    // The recorded config resolves against its folder; run from the source tree as CI does.
    const fs::path previous = fs::current_path();
    fs::current_path(RTBENCH_SOURCE_DIR);
    std::ostringstream clean;
    const CheckResult same = checkResults(copy.string(), 10.0, clean);
    EXPECT_EQ(same.deterministicDifferences, 0) << clean.str();
    EXPECT_EQ(same.runs, 8);

    std::vector<Row> rows = readCsv((copy / "runs.csv").string());
    ASSERT_EQ(rows.size(), 8u);
    const std::string recorded = rows[3].at("passes_total");
    rows[3]["passes_total"] = std::to_string(std::stoull(recorded) + 1);
    writeCsv((copy / "runs.csv").string(), runColumns(), rows);
    std::ostringstream report;
    const CheckResult changed = checkResults(copy.string(), 10.0, report);
    fs::current_path(previous);
    EXPECT_EQ(changed.deterministicDifferences, 1);
    EXPECT_THAT(report.str(), HasSubstr("1 deterministic difference(s)"));
    EXPECT_THAT(report.str(), HasSubstr("passes_total"));
    EXPECT_THAT(report.str(), HasSubstr(recorded));
}

}  // namespace
}  // namespace rtbench
