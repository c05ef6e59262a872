// What rtbench guarantees about a results folder (README, "Results folders"): a run's identity
// covers every input it used (parameters, commit, device, file contents), resume keeps only rows
// of that identity and sets the others aside, merge joins only shards of one experiment, nothing
// is written through a symlink, and no shell ever runs.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "harness/check.h"
#include "harness/columns.h"
#include "harness/config.h"
#include "harness/output_folder.h"
#include "harness/runner.h"
#include "harness/shard_merge.h"
#include "harness/timing_rounds.h"
#include "scene/mesh_io.h"
#include "tests/device/test_device.h"
#include "tests/error_of.h"
#include "tests/temp_dir.h"

namespace rtbench {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;

constexpr const char* kTwoTriangles = "OFF\n4 2 0\n-1 -1 0\n1 -1 0\n1 1 0\n-1 1 0\n3 0 1 2\n3 0 2 3\n";
constexpr const char* kOneTriangle = "OFF\n4 1 0\n-1 -1 0\n1 -1 0\n1 1 0\n-1 1 0\n3 0 1 2\n";

std::string readText(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

class ResultsFolder : public ::testing::Test {
  protected:
    ExperimentPlan plan(const std::string& body) {
        const std::string path = dir_.write("r.toml", "[experiment]\nname = \"r\"\noutput = \"" + dir_.file("out") +
                                                          "\"\nrepetitions = 1\nwarmups = 0\n[device]\nname = \"" +
                                                          testDeviceName() + "\"\n[camera]\nwidth = 8\nheight = 6\n"
                                                          "[output]\nimages = false\nhit_records = " +
                                                          (hitRecords_ ? "true" : "false") + "\n" + body);
        return loadExperiment(path);
    }
    ExperimentResult run(const std::string& body, RunnerOptions options = quiet()) {
        return runExperiment(plan(body), options);
    }
    static RunnerOptions quiet() {
        RunnerOptions o;
        o.quiet = true;
        return o;
    }
    static RunnerOptions shard(unsigned i, unsigned n) {
        RunnerOptions o = quiet();
        o.shardIndex = i;
        o.shardCount = n;
        return o;
    }
    fs::path folder() const { return dir_.path() / "out" / "r"; }
    // Everything set aside, or only the rows (superseded-*-runs.csv).
    std::vector<fs::path> superseded(bool rowsOnly = true) const {
        std::vector<fs::path> files;
        for (const auto& e : fs::directory_iterator(folder())) {
            const std::string name = e.path().filename().string();
            if (name.rfind("superseded-", 0) == 0 && (!rowsOnly || name.ends_with("-runs.csv"))) files.push_back(e.path());
        }
        return files;
    }
    TempDir dir_;
    bool hitRecords_ = false;
};

const std::string kMeshSweep = "[scene]\nsource = \"flat.off\"\n[structure]\nmin_dim = [2, 3]\n";

// Replace a mesh file and run again: the rows traced on the old mesh are not kept.
TEST_F(ResultsFolder, AChangedMeshFileIsAnotherRun) {
    dir_.write("flat.off", kTwoTriangles);
    const ExperimentResult first = run(kMeshSweep);
    ASSERT_EQ(first.failed, 0) << first.rows[0].at("error");
    EXPECT_EQ(first.rows[0].at("scene_triangles"), "2");
    EXPECT_EQ(first.rows[0].at("input_files").find(dir_.file("flat.off") + " (" + std::to_string(std::string(kTwoTriangles).size()) + " bytes, fnv1a64 "), 0u);
    EXPECT_EQ(run(kMeshSweep).reused, 2);  // the same file: kept
    dir_.write("flat.off", kOneTriangle);
    const ExperimentResult again = run(kMeshSweep);
    EXPECT_EQ(again.reused, 0);
    EXPECT_EQ(again.rows[0].at("scene_triangles"), "1");
    EXPECT_NE(again.rows[0].at("inputs_hash"), first.rows[0].at("inputs_hash"));
    // The rows of the old mesh are set aside, not lost, with the context they were run under.
    ASSERT_EQ(superseded().size(), 1u);
    const fs::path csv = superseded()[0];
    EXPECT_EQ(readCsv(csv.string()).at(1).at("scene_triangles"), "2");
    const std::string prefix = csv.string().substr(0, csv.string().size() - std::string("runs.csv").size());
    EXPECT_TRUE(fs::exists(prefix + "context.json"));
}

// A superseded row's per-run files go with it: no old hit records beside a new row of its run.
TEST_F(ResultsFolder, ASupersededRowTakesItsPerRunFilesAside) {
    dir_.write("flat.off", kTwoTriangles);
    hitRecords_ = true;
    const std::string body = "[scene]\nsource = \"flat.off\"\n[structure]\nmin_dim = 2\n";
    ASSERT_EQ(run(body).failed, 0);
    ASSERT_TRUE(fs::exists(folder() / "run-000.hits"));
    dir_.write("flat.off", "OFF\n3 1 0\n");  // the run fails now: it writes no hit records
    EXPECT_EQ(run(body).failed, 1);
    EXPECT_FALSE(fs::exists(folder() / "run-000.hits"));
    bool aside = false;
    for (const fs::path& f : superseded(false)) aside = aside || f.string().ends_with("-run-000.hits");
    EXPECT_TRUE(aside);
}

// A last row cut while written is set aside and its run run again; check calls it cut.
TEST_F(ResultsFolder, ACutLastRowIsSetAsideAndRunAgain) {
    const std::string body = "[scene]\nsource = \"procedural:christen_a\"\n[structure]\nmin_dim = [2, 3]\n";
    run(body);
    const fs::path csv = folder() / "runs.csv";
    std::string text = readText(csv);
    text.resize(text.size() - 3);  // inside wall_s, the last column: the field count still fits
    std::ofstream(csv, std::ios::binary) << text;
    EXPECT_THAT(errorOf([&] { readRunsCsv(csv.string()); }), HasSubstr(":3: the last row has no line end (cut while written?)"));
    const ExperimentResult again = run(body);
    EXPECT_EQ(again.reused, 1);  // run 000; run 001 again
    bool cut = false;
    for (const fs::path& f : superseded(false)) cut = cut || f.extension() == ".cut-row";
    EXPECT_TRUE(cut);
    EXPECT_EQ(readRunsCsv(csv.string()).size(), 2u);
}

// An interrupted sweep that finished no run: check re-runs nothing (not the whole plan).
TEST_F(ResultsFolder, CheckOfAFolderWithNoRowsReRunsNothing) {
    run("[scene]\nsource = \"procedural:christen_a\"\n[structure]\nmin_dim = 2\n");
    writeCsv((folder() / "runs.csv").string(), runColumns(), {});
    Json context = readJson((folder() / "context.json").string());
    context["complete"] = false;
    writeJson((folder() / "context.json").string(), context);
    std::ostringstream out;
    const CheckResult r = checkResults(folder().string(), {}, out);
    EXPECT_EQ(r.runs, 0);
    EXPECT_THAT(out.str(), HasSubstr("0 runs recorded"));
    context["complete"] = "yes";
    writeJson((folder() / "context.json").string(), context);
    EXPECT_THAT(errorOf([&] { checkResults(folder().string(), {}, out); }),
                HasSubstr("context.json: no boolean \"complete\" field"));
}

TEST_F(ResultsFolder, MergeRefusesShardsOfAnotherCpu) {
    dir_.write("flat.off", kTwoTriangles);
    run(kMeshSweep, shard(0, 2));
    run(kMeshSweep, shard(1, 2));
    const std::string csv = (folder() / "runs.shard-1-of-2.csv").string();
    std::vector<Row> rows = readRunsCsv(csv);
    rows[0]["cpu"] = "Another CPU";
    writeCsv(csv, runColumns(), rows);
    EXPECT_THAT(errorOf([&] { mergeShards(folder().string()); }),
                HasSubstr("with Another CPU; a merged runs.csv holds one device and CPU"));
}

// A scene description's own text and every mesh it places are inputs.
TEST_F(ResultsFolder, AChangedMeshInASceneDescriptionIsAnotherRun) {
    dir_.write("flat.off", kTwoTriangles);
    dir_.write("scene.toml", "[[object]]\nmesh = \"flat.off\"\n");
    const std::string body = "[scene]\nsource = \"scene.toml\"\n[structure]\nmin_dim = 2\n";
    const ExperimentResult first = run(body);
    ASSERT_EQ(first.failed, 0) << first.rows[0].at("error");
    EXPECT_THAT(first.rows[0].at("input_files"), HasSubstr("scene.toml ("));
    EXPECT_THAT(first.rows[0].at("input_files"), HasSubstr("; " + dir_.file("flat.off") + " ("));
    dir_.write("flat.off", kOneTriangle);
    EXPECT_EQ(run(body).reused, 0);
}

// Shard 0 on one mesh, shard 1 on another: merge refuses, naming both.
TEST_F(ResultsFolder, MergeRefusesShardsThatReadOtherContents) {
    dir_.write("flat.off", kTwoTriangles);
    run(kMeshSweep, shard(0, 2));
    dir_.write("flat.off", kOneTriangle);
    run(kMeshSweep, shard(1, 2));
    EXPECT_THAT(errorOf([&] { mergeShards(folder().string()); }),
                HasSubstr("runs 000 and 001 read other contents of scene.source 'flat.off'"));
    EXPECT_FALSE(fs::exists(folder() / "runs.csv"));
}

TEST_F(ResultsFolder, MergeRefusesShardsOfAnotherCommitOrConfig) {
    dir_.write("flat.off", kTwoTriangles);
    run(kMeshSweep, shard(0, 2));
    run(kMeshSweep, shard(1, 2));
    const fs::path context = folder() / "context.shard-1-of-2.json";
    Json json = readJson(context.string());
    const Json saved = json;
    json["git_commit"] = "0000000000ab";
    writeJson(context.string(), json);
    EXPECT_THAT(errorOf([&] { mergeShards(folder().string()); }), HasSubstr("were run at other commits"));
    json = saved;
    json["config_text"] = json["config_text"].get<std::string>() + "\n# another config\n";
    writeJson(context.string(), json);
    EXPECT_THAT(errorOf([&] { mergeShards(folder().string()); }), HasSubstr("the plans differ"));
    writeJson(context.string(), saved);
    // A row kept from another commit in a shard's CSV, though the contexts agree.
    const std::string shardCsv = (folder() / "runs.shard-1-of-2.csv").string();
    const std::vector<Row> shardRows = readRunsCsv(shardCsv);
    std::vector<Row> edited = shardRows;
    edited[0]["git_commit"] = "0000000000ab";
    writeCsv(shardCsv, runColumns(), edited);
    EXPECT_THAT(errorOf([&] { mergeShards(folder().string()); }), HasSubstr("was run at commit 0000000000ab"));
    writeCsv(shardCsv, runColumns(), shardRows);
    EXPECT_EQ(mergeShards(folder().string()).size(), 2u);
    EXPECT_EQ(mergeShards(folder().string()).size(), 2u);  // merging again changes nothing
    // An existing, different runs.csv is not replaced.
    std::vector<Row> rows = readRunsCsv((folder() / "runs.csv").string());
    rows.pop_back();
    writeCsv((folder() / "runs.csv").string(), runColumns(), rows);
    EXPECT_THAT(errorOf([&] { mergeShards(folder().string()); }),
                HasSubstr("runs.csv: exists and differs from the merge of these shards (1 rows against 2)"));
}

// A shard killed mid-run (its CSV holds the header alone) and a shard never started: merge
// refuses, unless asked to write each missing run as a failed row with the reason given; those
// rows carry the run's identity as the runner would have written it.
TEST_F(ResultsFolder, MergeWritesRunsNoShardFinishedAsFailedRowsWhenAsked) {
    dir_.write("flat.off", kTwoTriangles);
    const std::string sweep = "[scene]\nsource = \"flat.off\"\n[structure]\nmin_dim = [2, 3, 4]\n";
    const ExperimentResult whole = run(sweep);
    ASSERT_EQ(whole.failed, 0);
    fs::remove_all(folder());
    run(sweep, shard(0, 3));
    run(sweep, shard(1, 3));
    const std::string killed = (folder() / "runs.shard-1-of-3.csv").string();
    writeCsv(killed, runColumns(), {});  // as a process killed during its run leaves it
    EXPECT_THAT(errorOf([&] { mergeShards(folder().string()); }), HasSubstr("run 001 is missing from the shards"));
    EXPECT_FALSE(fs::exists(folder() / "runs.csv"));
    const std::vector<Row> merged = mergeShards(folder().string(), "killed after 60 s (the campaign's cap)");
    ASSERT_EQ(merged.size(), 3u);
    EXPECT_EQ(merged[0].at("status"), "ok");
    for (std::size_t k : {1u, 2u}) {
        const Row& failed = merged[k];
        EXPECT_EQ(failed.at("status"), "failed");
        EXPECT_EQ(failed.at("error"), "no row from its shard: killed after 60 s (the campaign's cap)");
        for (const char* column : {"run", "label", "sweep", "config_hash", "git_commit", "device", "driver", "cpu", "structure_min_dim"})
            EXPECT_EQ(failed.at(column), whole.rows[k].at(column)) << column;
    }
    EXPECT_EQ(readRunsCsv((folder() / "runs.csv").string()), merged);
    EXPECT_FALSE(readJson((folder() / "context.json").string()).at("complete").get<bool>());
    // Run 001 finished its samples before the "kill" emptied its CSV: they go with its row.
    const std::vector<Row> samples = readSamplesCsv((folder() / "samples.csv").string());
    EXPECT_FALSE(samples.empty());
    for (const Row& sample : samples) EXPECT_EQ(sample.at("run"), "000");
}

// Shards run side by side (each holds its own lock); the same shard twice, or a whole-folder run
// or merge during a shard, is refused at once.
TEST_F(ResultsFolder, ShardsLockTheirOwnFilesAndMergeTheFolder) {
    fs::create_directories(folder());
    const OutputFolderLock zero(folder().string(), "shard-0-of-2");
    EXPECT_NO_THROW(OutputFolderLock one(folder().string(), "shard-1-of-2"));
    EXPECT_THAT(errorOf([&] { OutputFolderLock again(folder().string(), "shard-0-of-2"); }),
                HasSubstr("is writing shard-0-of-2 of this results folder"));
    EXPECT_THAT(errorOf([&] { OutputFolderLock whole(folder().string()); }),
                HasSubstr("shard runs (pid " + std::to_string(::getpid()) + ") are writing this results folder"));
}

// The last holder removes a lock file; a lock on a removed file is taken again on the new one.
TEST_F(ResultsFolder, LockFilesAreRemovedByTheirLastHolder) {
    fs::create_directories(folder());
    {
        const OutputFolderLock whole(folder().string());
        EXPECT_TRUE(fs::exists(folder() / ".rtbench.lock"));
    }
    EXPECT_FALSE(fs::exists(folder() / ".rtbench.lock"));
    {
        const OutputFolderLock zero(folder().string(), "shard-0-of-2");
        {
            const OutputFolderLock one(folder().string(), "shard-1-of-2");
        }
        EXPECT_FALSE(fs::exists(folder() / ".rtbench.shard-1-of-2.lock"));
        EXPECT_TRUE(fs::exists(folder() / ".rtbench.lock"));  // shard 0 still holds it, shared
        EXPECT_THAT(errorOf([&] { OutputFolderLock whole(folder().string()); }),
                    HasSubstr("shard runs (pid " + std::to_string(::getpid()) + ")"));
    }
    EXPECT_FALSE(fs::exists(folder() / ".rtbench.lock"));
    EXPECT_FALSE(fs::exists(folder() / ".rtbench.shard-0-of-2.lock"));
    // A run leaves none behind.
    run("[scene]\nsource = \"procedural:christen_a\"\n[structure]\nmin_dim = 2\n");
    for (const auto& entry : fs::directory_iterator(folder()))
        EXPECT_EQ(entry.path().filename().string().find(".lock"), std::string::npos) << entry.path();
}

// -d and --validation are the run's parameters: recorded as they took effect, and a change makes
// another run. A device that is not there fails the command before anything is written.
TEST_F(ResultsFolder, TheEffectiveDeviceAndValidationAreTheRunsIdentity) {
    const std::string body = "[scene]\nsource = \"procedural:christen_a\"\n[structure]\nmin_dim = 2\n";
    EXPECT_EQ(run(body).reused, 0);
    EXPECT_EQ(run(body).reused, 1);
    ExperimentPlan validated = plan(body);
    overrideKey(validated, "device.validation", true, "--validation");
    const ExperimentResult v = runExperiment(validated, quiet());
    EXPECT_EQ(v.reused, 0);
    EXPECT_EQ(v.rows[0].at("device_validation"), "true");
    ExperimentPlan missing = plan(body);
    overrideKey(missing, "device.name", std::string("nosuchgpu"), "-d");
    const std::string before = readText(folder() / "runs.csv");
    EXPECT_THAT(errorOf([&] { runExperiment(missing, quiet()); }), HasSubstr("nosuchgpu"));
    EXPECT_EQ(readText(folder() / "runs.csv"), before);
    // check re-runs with the recorded overrides.
    std::ostringstream report;
    EXPECT_FALSE(checkResults(folder().string(), {}, report).failed()) << report.str();
}

// Shrinking a sweep: the dropped run is named and saved, the kept run's label is this plan's, and
// the folder passes check.
TEST_F(ResultsFolder, AShrunkSweepSetsTheDroppedRowsAsideAndStaysConsistent) {
    run("[scene]\nsource = \"procedural:christen_a\"\n[structure]\nmin_dim = [2, 3]\n");
    const ExperimentResult shrunk = run("[scene]\nsource = \"procedural:christen_a\"\n[structure]\nmin_dim = [2]\n");
    EXPECT_EQ(shrunk.reused, 1);
    ASSERT_EQ(shrunk.rows.size(), 1u);
    EXPECT_EQ(shrunk.rows[0].at("label"), "single run");
    ASSERT_EQ(superseded().size(), 1u);
    EXPECT_EQ(readCsv(superseded()[0].string()).at(0).at("label"), "structure.min_dim=3");
    std::ostringstream report;
    EXPECT_FALSE(checkResults(folder().string(), {}, report).failed()) << report.str();
}

// A row of another commit is re-run (the binary changed), and the old row is set aside.
TEST_F(ResultsFolder, AResumeAcrossACommitReRunsTheRow) {
    const std::string body = "[scene]\nsource = \"procedural:christen_a\"\n[structure]\nmin_dim = 2\n";
    run(body);
    std::vector<Row> rows = readRunsCsv((folder() / "runs.csv").string());
    rows[0]["git_commit"] = "0123456789ab";
    writeCsv((folder() / "runs.csv").string(), runColumns(), rows);
    const ExperimentResult again = run(body);
    EXPECT_EQ(again.reused, 0);
    EXPECT_NE(again.rows[0].at("git_commit"), "0123456789ab");
    ASSERT_EQ(superseded().size(), 1u);
    EXPECT_EQ(readCsv(superseded()[0].string()).at(0).at("git_commit"), "0123456789ab");
}

// A row is kept on resume only with its own samples: forged, duplicated or missing samples re-run
// the run (the old row set aside), and an untouched folder resumes whole.
TEST_F(ResultsFolder, AResumeReRunsARowWhoseSamplesAreNotItsOwn) {
    const std::string body = "[scene]\nsource = \"procedural:christen_a\"\n[structure]\nmin_dim = [2, 3]\n";
    run(body);
    EXPECT_EQ(run(body).reused, 2);
    const std::string samplesPath = (folder() / "samples.csv").string();
    std::vector<Row> samples = readCsv(samplesPath);
    for (Row& sample : samples)
        if (sample.at("run") == "001" && sample.at("method") == "kernel") sample["ms"] = "1e6";
    writeCsv(samplesPath, sampleColumns(), samples);
    const ExperimentResult again = run(body);
    EXPECT_EQ(again.reused, 1) << "run 000 kept, run 001 run again";
    ASSERT_EQ(superseded().size(), 1u);
    EXPECT_EQ(readCsv(superseded()[0].string()).at(0).at("run"), "001");
    fs::remove(samplesPath);
    EXPECT_EQ(run(body).reused, 0) << "no samples: nothing kept";
}

// Nothing is written through a symlink: a planted link in the folder (the lock, runs.csv, a
// temporary's name) refuses the folder and leaves the link's target untouched.
TEST_F(ResultsFolder, ASymlinkInTheFolderIsRefusedAndItsTargetUntouched) {
    const std::string body = "[scene]\nsource = \"procedural:christen_a\"\n[structure]\nmin_dim = 2\n";
    const std::string victim = dir_.write("victim.txt", "precious\n");
    for (const char* name : {".rtbench.lock", "runs.csv", "context.json", "runs.csv.tmp", "context.json.tmp",
                             ".runs.csv.tmp-000000", "run-000.hits"}) {
        fs::remove_all(folder());
        fs::create_directories(folder());
        fs::create_symlink(victim, folder() / name);
        EXPECT_THAT(errorOf([&] { run(body); }), HasSubstr("symlink")) << name;
        EXPECT_EQ(readText(victim), "precious\n") << name;
    }
    // The results folder itself a symlink.
    fs::remove_all(folder());
    fs::create_directories(dir_.path() / "elsewhere");
    fs::create_symlink(dir_.path() / "elsewhere", folder());
    EXPECT_THAT(errorOf([&] { run(body); }), HasSubstr("the results folder is a symlink"));
    EXPECT_TRUE(fs::is_empty(dir_.path() / "elsewhere"));
}

// CGAL's meshes are extracted with libarchive: no shell, so a cache path with quotes is a path.
TEST_F(ResultsFolder, TheCgalCacheRunsNoShellAndCatchesAChangedFile) {
    const fs::path cache = dir_.path() / "x'; touch PWNED; echo '";
    const char* saved = std::getenv("RTBENCH_CACHE");
    const std::string savedValue = saved ? saved : "";
    ::setenv("RTBENCH_CACHE", cache.c_str(), 1);
    const fs::path cwd = fs::current_path();
    fs::current_path(dir_.path());
    const TriangleMesh cube = readCgalMesh("cube");
    EXPECT_EQ(cube.triangles.size(), 12u);
    EXPECT_FALSE(fs::exists(dir_.path() / "PWNED"));
    // A cached mesh replaced by another is refused, not traced.
    const std::string file = resolveCgalMesh("cube");
    std::ofstream(file, std::ios::binary) << kOneTriangle;
    EXPECT_THAT(errorOf([&] { readCgalMesh("cube"); }), HasSubstr("differs from the file extracted from libcgal-demo"));
    // An emptied cache is extracted again, not reported as "no such mesh".
    fs::remove_all(cache / "cgal-data" / "meshes");
    fs::create_directories(cache / "cgal-data" / "meshes");
    fs::remove(cache / "cgal-data" / ".extracted");
    EXPECT_EQ(readCgalMesh("cube").triangles.size(), 12u);
    EXPECT_THAT(errorOf([&] { resolveCgalMesh("no_such_mesh"); }), HasSubstr("no such mesh in libcgal-demo (1"));
    fs::current_path(cwd);
    if (saved) ::setenv("RTBENCH_CACHE", savedValue.c_str(), 1);
    else ::unsetenv("RTBENCH_CACHE");
}

TEST_F(ResultsFolder, ASymlinkLoopMeshIsNamedSo) {
    fs::create_symlink("loop.off", dir_.path() / "loop.off");
    const ExperimentResult r = run("[scene]\nsource = \"loop.off\"\n");
    EXPECT_EQ(r.rows[0].at("error"), dir_.file("loop.off") + ": mesh file is a symlink loop (too many levels of symbolic links)");
}

// check reads runs.csv only as a regular file.
TEST_F(ResultsFolder, CheckRefusesARunsCsvThatIsNotARegularFile) {
    run("[scene]\nsource = \"procedural:christen_a\"\n[structure]\nmin_dim = 2\n");
    fs::remove(folder() / "runs.csv");
    ASSERT_EQ(::mkfifo((folder() / "runs.csv").c_str(), 0644), 0);
    std::ostringstream out;
    EXPECT_THAT(errorOf([&] { checkResults(folder().string(), {}, out); }),
                HasSubstr("runs.csv: the CSV file is a FIFO, not a regular file"));
}

}  // namespace
}  // namespace rtbench
