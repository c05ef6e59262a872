// rtbench check: each column compared by its kind; the goldens reproduce under every Embree ISA
// this CPU runs; a changed count, a malformed CSV or a missing column fails with its name.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "harness/check.h"
#include "harness/timing_rounds.h"
#include "harness/embree_config.h"
#include "harness/runner.h"
#include "core/error.h"
#include "tests/error_of.h"
#include "tests/temp_dir.h"

namespace rtbench {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

TEST(Check, EveryColumnHasTheKindItsValueHas) {
    EXPECT_EQ(columnSpec("kernel_ms_median").kind, ColumnKind::Timing);
    EXPECT_EQ(columnSpec("embree16_mrays_s").kind, ColumnKind::Timing);
    EXPECT_EQ(columnSpec("grid_build_ms").kind, ColumnKind::Timing);
    EXPECT_EQ(columnSpec("passes_total").kind, ColumnKind::Exact);
    EXPECT_EQ(columnSpec("bytes_stencil").kind, ColumnKind::Exact);
    EXPECT_EQ(columnSpec("hits").kind, ColumnKind::Exact);
    // Derived from Embree's floating point: never an exact count.
    EXPECT_EQ(columnSpec("hit_miss_agreement").kind, ColumnKind::Reference);
    EXPECT_EQ(columnSpec("rel_distance_error_mean").kind, ColumnKind::Reference);
    EXPECT_EQ(columnSpec("primitive_mismatches").kind, ColumnKind::Reference);
    EXPECT_EQ(columnSpec("embree_isa").kind, ColumnKind::Context);
    EXPECT_EQ(columnSpec("structure_min_dim").kind, ColumnKind::Parameter);
    EXPECT_THROW(columnSpec("hitz"), Error);
}

// A per-ray tolerance scales with the recorded run's rays: hit_miss_mismatches may move by 1e-4
// per ray, so by 1 over 10,000 rays (within) but not over 1,000 (beyond: 0.1 allowed).
TEST(Check, APerRayToleranceScalesWithTheRunsRays) {
    const Row recorded = {{"run", "000"}, {"rays", "10000"}, {"hit_miss_mismatches", "5"}};
    Row rerun = recorded;
    rerun["hit_miss_mismatches"] = "6";
    EXPECT_TRUE(deterministicDifferences(recorded, rerun).empty());
    Row fewer = recorded, fewerRerun = rerun;
    fewer["rays"] = fewerRerun["rays"] = "1000";
    const std::vector<std::string> beyond = deterministicDifferences(fewer, fewerRerun);
    ASSERT_EQ(beyond.size(), 1u);
    EXPECT_THAT(beyond.front(), HasSubstr("reference (tolerance 0.1): BEYOND"));
    rerun["hit_miss_mismatches"] = "7";  // 2 over 10,000 rays: beyond 1
    EXPECT_EQ(deterministicDifferences(recorded, rerun).size(), 1u);
}

// A copy of results/golden to tamper with; the check runs from the source tree as CI does.
class Golden : public ::testing::Test {
  protected:
    void SetUp() override {
        fs::copy(fs::path(RTBENCH_SOURCE_DIR) / "results" / "golden", copy_);
        previous_ = fs::current_path();
        fs::current_path(RTBENCH_SOURCE_DIR);
    }
    void TearDown() override { fs::current_path(previous_); }
    std::string csv() const { return (copy_ / "runs.csv").string(); }
    std::string text() const {
        std::ifstream in(csv(), std::ios::binary);
        std::stringstream s;
        s << in.rdbuf();
        return s.str();
    }
    void setText(const std::string& t) const { std::ofstream(csv(), std::ios::binary) << t; }
    // The recorded file's columns (those of its results schema), to write it back with.
    std::vector<std::string> header() const {
        std::ifstream in((fs::path(RTBENCH_SOURCE_DIR) / "results" / "golden" / "runs.csv").string());
        std::string line, column;
        std::getline(in, line);
        std::vector<std::string> columns;
        std::istringstream fields(line);
        while (std::getline(fields, column, ',')) columns.push_back(column);
        return columns;
    }
    CheckResult check(std::ostream& out, const std::string& embreeConfig = "") const {
        return checkResults(copy_.string(),
                            {.timingTolerance = 10.0, .embreeConfigOverride = embreeConfig}, out);
    }
    // Keeps only `rows` of the recorded ones, as an interrupted sweep that finished just those
    // (check then re-runs only them: a check of one behaviour need not re-run all 38).
    void keepOnly(const std::vector<Row>& rows) const {
        Json context = readJson((copy_ / "context.json").string());
        context["complete"] = false;
        writeJson((copy_ / "context.json").string(), context);
        writeCsv(csv(), header(), rows);
    }
    std::string errorOfCheck() const {
        std::ostringstream out;
        try {
            check(out);
        } catch (const Error& e) {
            return e.what();
        }
        return "(no error) " + out.str();
    }
    TempDir dir_;
    fs::path copy_ = dir_.path() / "golden";
    fs::path previous_;
};

TEST_F(Golden, ReproducesAndAChangedCountFails) {
    std::ostringstream clean;
    const CheckResult same = check(clean);
    EXPECT_FALSE(same.failed()) << clean.str();
    EXPECT_EQ(same.runs, 38);

    std::vector<Row> rows = readCsv(csv());
    ASSERT_EQ(rows.size(), 38u);
    const std::string recorded = rows[3].at("passes_total");
    rows[3]["passes_total"] = std::to_string(std::stoull(recorded) + 1);
    keepOnly({rows[2], rows[3]});  // the changed run and one unchanged
    std::ostringstream report;
    const CheckResult changed = check(report);
    EXPECT_EQ(changed.runs, 2);
    EXPECT_EQ(changed.deterministicDifferences, 1);
    EXPECT_THAT(report.str(), HasSubstr("1 deterministic difference(s)"));
    EXPECT_THAT(report.str(), HasSubstr("passes_total"));
    EXPECT_THAT(report.str(), HasSubstr(recorded));
    EXPECT_THAT(report.str(), HasSubstr(" exact\n"));  // its kind, at the end of its line
}

// The samples behind the recorded timings are read too: a sample that is not the row's (here the
// kernel's one sample of run 002 forged) is a deterministic difference naming the run; so is a
// missing samples.csv.
TEST_F(Golden, SamplesThatAreNotTheRowsFail) {
    std::vector<Row> rows = readCsv(csv());
    keepOnly({rows[2]});
    std::vector<Row> samples = readCsv((copy_ / "samples.csv").string());
    for (Row& sample : samples)
        if (sample.at("run") == "002" && sample.at("method") == "kernel") sample["ms"] = "99.5";
    writeCsv((copy_ / "samples.csv").string(), sampleColumns(), samples);
    std::ostringstream report;
    const CheckResult forged = check(report);
    EXPECT_EQ(forged.deterministicDifferences, 1) << report.str();
    EXPECT_THAT(report.str(), HasSubstr("002   (samples.csv)"));
    EXPECT_THAT(report.str(), HasSubstr("the kernel samples' median 99.5 is not the row's kernel_ms_median"));
    fs::remove(copy_ / "samples.csv");
    std::ostringstream missing;
    EXPECT_TRUE(check(missing).failed());
    EXPECT_THAT(missing.str(), HasSubstr("-     (samples.csv)                 missing"));
}

// columns.csv tells a reader each column's kind: garbage there, or one that misses a column of
// runs.csv, fails the check by name; a folder's re-run by another commit is said.
TEST_F(Golden, AGarbageColumnsCsvFailsAndTheCommitDifferenceIsSaid) {
    std::vector<Row> rows = readCsv(csv());
    rows[0]["git_commit"] = "0123456789ab";  // recorded by another commit than this binary's, whichever that is
    keepOnly({rows[0]});
    std::ofstream((copy_ / "columns.csv").string(), std::ios::trunc) << "column,kind\n\"unclosed\n";
    std::ostringstream garbage;
    EXPECT_EQ(check(garbage).deterministicDifferences, 1) << garbage.str();
    EXPECT_THAT(garbage.str(), HasSubstr("(columns.csv)"));
    std::ofstream((copy_ / "columns.csv").string(), std::ios::trunc) << "column,kind\nrun,parameter\n";
    std::ostringstream partial;
    EXPECT_EQ(check(partial).deterministicDifferences, 1) << partial.str();
    EXPECT_THAT(partial.str(), HasSubstr("does not describe runs.csv's column"));
    EXPECT_THAT(partial.str(), HasSubstr("(recorded by commit 0123456789ab, re-run by commit "));
}

TEST_F(Golden, AReferenceValueBeyondItsToleranceFailsAndSaysItsKind) {
    std::vector<Row> rows = readCsv(csv());
    rows[0]["hit_miss_agreement"] = "0.9";  // Embree-dependent, but no ISA moves it this far
    keepOnly({rows[0]});
    std::ostringstream report;
    EXPECT_TRUE(check(report).failed());
    EXPECT_THAT(report.str(), HasSubstr("hit_miss_agreement"));
    EXPECT_THAT(report.str(), HasSubstr("reference (tolerance 0.0001): BEYOND"));
}

// The tolerance's edge: a reference value just within its tolerance passes (and is reported as
// within), just past it fails. hit_miss_mismatches' tolerance is per ray (1e-4 x 1536 rays =
// 0.1536 here), hit_miss_agreement's absolute (1e-4). One run is kept (an interrupted sweep), so
// only it is re-run.
TEST_F(Golden, AReferenceDifferenceJustWithinItsTolerancePassesAndJustPastFails) {
    const std::vector<Row> all = readCsv(csv());
    ASSERT_EQ(all[0].at("rays"), "1536");
    Json context = readJson((copy_ / "context.json").string());
    context["complete"] = false;
    writeJson((copy_ / "context.json").string(), context);
    struct Case {
        const char* column;
        double offset;
        bool fails;
    };
    for (const Case& c : {Case{"hit_miss_mismatches", 0.15, false}, Case{"hit_miss_mismatches", 0.16, true},
                          Case{"hit_miss_agreement", -0.99e-4, false}, Case{"hit_miss_agreement", -1.01e-4, true}}) {
        Row row = all[0];
        row[c.column] = formatNumber(std::stod(row.at(c.column)) + c.offset, 10);
        writeCsv(csv(), header(), {row});
        std::ostringstream report;
        EXPECT_EQ(check(report).failed(), c.fails) << c.column << " + " << c.offset << "\n" << report.str();
        EXPECT_THAT(report.str(), HasSubstr(c.fails ? ": BEYOND" : ": within")) << c.column << " + " << c.offset;
    }
}

// Embree takes another code path per ISA; the counts must not notice.
TEST_F(Golden, ReproducesWithEmbreeForcedToEveryIsaThisCpuRuns) {
    const std::vector<std::string> isas = embreeIsasSupportedHere();
    ASSERT_FALSE(isas.empty());
    for (const std::string& isa : isas) {
        std::ostringstream report;
        const CheckResult r = check(report, "isa=" + isa);
        EXPECT_FALSE(r.failed()) << "isa=" << isa << "\n" << report.str();
        EXPECT_EQ(r.runs, 38) << isa;
    }
}

TEST_F(Golden, CrlfLineEndingsReadTheSame) {
    const std::vector<Row> rows = readCsv(csv());
    keepOnly({rows[0], rows[1]});
    std::string t = text(), crlf;
    for (char c : t) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
    setText(crlf);
    std::ostringstream report;
    const CheckResult r = check(report);
    EXPECT_FALSE(r.failed()) << report.str();
    EXPECT_THAT(report.str(), Not(HasSubstr("\r")));
}

TEST_F(Golden, AMissingColumnIsAnErrorNamingIt) {
    std::vector<Row> rows = readCsv(csv());
    std::vector<std::string> columns = header();
    std::erase(columns, "hits");
    for (Row& r : rows) r.erase("hits");
    writeCsv(csv(), columns, rows);
    EXPECT_THAT(errorOfCheck(), HasSubstr("missing column(s) hits"));

    columns = header();
    std::erase(columns, "run");
    rows = readCsv((fs::path(RTBENCH_SOURCE_DIR) / "results/golden/runs.csv").string());
    for (Row& r : rows) r.erase("run");
    writeCsv(csv(), columns, rows);
    EXPECT_THAT(errorOfCheck(), HasSubstr("missing column(s) run"));
}

// A file of the newest schema that lacks one of its columns was cut or edited: an error naming
// the column, not a file of an older schema.
TEST(Columns, AFileMissingSomeOfASchemasColumnsIsAnError) {
    std::vector<std::string> columns = runColumns();
    Row row;
    for (const std::string& c : columns) row[c] = "";
    row["run"] = "000";
    std::erase(columns, "kernel_ms_ci_low");
    row.erase("kernel_ms_ci_low");
    TempDir dir;
    const std::string path = dir.file("runs.csv");
    writeCsv(path, columns, {row});
    EXPECT_THAT(errorOf([&] { readRunsCsv(path); }), HasSubstr("missing column(s) kernel_ms_ci_low (of results schema 5"));
    // Without any schema-5 column it is a schema-4 file, and reads.
    std::vector<std::string> older;
    for (const ColumnSpec& c : runColumnSpecs())
        if (c.since < 5) older.push_back(c.name);
    Row old;
    for (const std::string& c : older) old[c] = "";
    old["run"] = "000";
    writeCsv(path, older, {old});
    EXPECT_EQ(readRunsCsv(path).size(), 1u);
}

// Before schema 6 a 3-vector key was one "[x y z]" cell: a reader sees its three columns.
TEST(Columns, AnOlderFilesVectorCellsAreSplitIntoThreeColumns) {
    std::vector<std::string> columns;
    Row row;
    for (const std::string& c : runColumns()) {
        if (columnSpec(c).since > 5) continue;  // a schema-5 file
        const bool component = c.size() > 2 && (c.ends_with("_x") || c.ends_with("_y") || c.ends_with("_z")) &&
                               columnSpec(c).kind == ColumnKind::Parameter;
        const std::string name = component ? c.substr(0, c.size() - 2) : c;
        if (std::find(columns.begin(), columns.end(), name) == columns.end()) columns.push_back(name);
        row[name] = component ? "[0.5 -2 1e-3]" : "";
    }
    ASSERT_TRUE(row.count("camera_up") && row.count("scene_translate") && row.count("camera_position"));
    row["run"] = "000";
    row["camera_position"] = "";  // unset: three empty cells
    TempDir dir;
    const std::string path = dir.file("runs.csv");
    writeCsv(path, columns, {row});
    int schema = 0;
    const std::vector<Row> rows = readRunsCsv(path, &schema);
    EXPECT_EQ(schema, 5);
    EXPECT_EQ(rows.at(0).at("camera_up_x"), "0.5");
    EXPECT_EQ(rows.at(0).at("camera_up_y"), "-2");
    EXPECT_EQ(rows.at(0).at("scene_translate_z"), "1e-3");
    EXPECT_EQ(rows.at(0).at("camera_position_y"), "");
    EXPECT_FALSE(rows.at(0).count("camera_up"));
    // Today's file reads as today's schema.
    Row now;
    for (const std::string& c : runColumns()) now[c] = "";
    now["run"] = "000";
    writeCsv(path, runColumns(), {now});
    readRunsCsv(path, &schema);
    EXPECT_EQ(schema, kSchemaVersion);
    // A cell that is not three numbers in brackets is an error naming the row and column.
    for (const char* bad : {"[1 2]", "1 2 3", "[1 2 3 4]", "[1 x 3]"}) {
        row["camera_up"] = bad;
        writeCsv(path, columns, {row});
        EXPECT_THAT(errorOf([&] { readRunsCsv(path); }), HasSubstr("row 1, column camera_up: '" + std::string(bad) + "' is not a 3-vector"));
    }
}

TEST_F(Golden, ACutRowIsAnErrorNamingItsLine) {
    const std::string t = text();
    std::size_t third = t.find('\n', t.find('\n', t.find('\n') + 1) + 1);  // end of line 3
    std::size_t lineStart = t.rfind('\n', third - 1) + 1;
    std::string cut = t.substr(0, lineStart);
    std::size_t fields = 0, at = lineStart;
    for (bool quoted = false; fields < 10; ++at) {  // the first 10 fields, commas inside quotes skipped
        if (t[at] == '"') quoted = !quoted;
        if (t[at] == ',' && !quoted) ++fields;
    }
    cut += t.substr(lineStart, at - 1 - lineStart) + t.substr(third);
    setText(cut);
    EXPECT_THAT(errorOfCheck(), HasSubstr("runs.csv:3: row 2 has 10 of the header's"));
}

TEST_F(Golden, ADuplicatedRowIsAnError) {
    std::vector<Row> rows = readCsv(csv());
    rows.push_back(rows[2]);
    writeCsv(csv(), header(), rows);
    EXPECT_THAT(errorOfCheck(), HasSubstr("run 002 appears more than once"));
}

TEST_F(Golden, AnUnclosedQuoteIsAnErrorNamingItsLine) {
    const std::string original = text();
    std::string t = original;
    t.insert(t.find('\n', t.find('\n') + 1) + 1,
             "\"");  // start of line 3: closes at the next quote
    setText(t);
    EXPECT_THAT(errorOfCheck(), HasSubstr("runs.csv:3: text after a closing quote"));
    t = original;
    t.insert(t.find('\n', t.find('\n') + 1) + 4, "\"");  // inside the first field of line 3
    setText(t);
    EXPECT_THAT(errorOfCheck(), HasSubstr("runs.csv:3: a quote inside an unquoted field"));
    setText(original + "\"never closed");
    EXPECT_THAT(errorOfCheck(), HasSubstr("a quoted field is never closed"));
}

TEST_F(Golden, AnInterruptedSweepChecksTheRunsItFinished) {
    std::vector<Row> rows = readCsv(csv());
    rows.resize(3);
    writeCsv(csv(), header(), rows);
    Json context = readJson((copy_ / "context.json").string());
    context["complete"] = false;
    writeJson((copy_ / "context.json").string(), context);
    std::ostringstream report;
    const CheckResult r = check(report);
    EXPECT_FALSE(r.failed()) << report.str();
    EXPECT_EQ(r.runs, 3);
}

// Nothing lost: a completed sweep whose runs.csv lost a row (or every row), or whose plan was cut
// down, is an error naming the run, not a pass over what is left.
TEST_F(Golden, ALostRowOfACompletedSweepIsAnErrorNamingTheRun) {
    std::vector<Row> rows = readCsv(csv());
    const Row lost = rows[5];
    rows.erase(rows.begin() + 5);
    writeCsv(csv(), header(), rows);
    EXPECT_THAT(errorOfCheck(), HasSubstr("runs.csv: run " + lost.at("run") + " (" + lost.at("label") +
                                          ") of the plan has no row"));
    writeCsv(csv(), header(), {});  // header only
    EXPECT_THAT(errorOfCheck(), HasSubstr("runs.csv: run 000 "));
}

TEST_F(Golden, APlanCutDownInContextJsonIsAnError) {
    Json context = readJson((copy_ / "context.json").string());
    context["plan"].erase(context["plan"].size() - 1);
    writeJson((copy_ / "context.json").string(), context);
    EXPECT_THAT(errorOfCheck(), HasSubstr("context.json: its plan lacks run 037"));
}

TEST_F(Golden, ARowOfAnotherConfigIsAnError) {
    std::vector<Row> rows = readCsv(csv());
    rows[2]["config_hash"] = "0123456789abcdef";
    writeCsv(csv(), header(), rows);
    EXPECT_THAT(errorOfCheck(), HasSubstr("run 002 has config_hash 0123456789abcdef"));
    rows[2] = rows[1];
    rows[2]["run"] = "038";
    writeCsv(csv(), header(), rows);
    EXPECT_THAT(errorOfCheck(), HasSubstr("run 038 (" + rows[2].at("label") + ") is not in the recorded plan"));
}

TEST(CheckTolerance, ANegativeOrNanToleranceIsRefused) {
    std::ostringstream out;
    for (double bad : {-1.0, std::nan(""), double(INFINITY)})
        EXPECT_THAT(errorOf([&] { checkResults(RTBENCH_SOURCE_DIR "/results/golden", {.timingTolerance = bad}, out); }),
                    HasSubstr("--tolerance"));
}

TEST(CheckOptions, ABogusEmbreeConfigIsRefused) {
    std::ostringstream out;
    try {
        checkResults(RTBENCH_SOURCE_DIR "/results/golden", {.embreeConfigOverride = "isa=bogus"},
                     out);
        FAIL();
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr("--embree-config: isa=bogus: unknown ISA (allowed: sse2, "
                                        "sse4.2, avx, avx2, avx512)"));
    }
}

}  // namespace
}  // namespace rtbench
