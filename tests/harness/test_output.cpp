// The results folder and its files: one writer at a time, nothing outside -o, nothing computed
// and then lost, nothing half-written, nothing undeclared, text that is valid UTF-8.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "harness/columns.h"
#include "harness/compare.h"
#include "harness/interrupt_note.h"
#include "harness/config.h"
#include "harness/output_folder.h"
#include "harness/runner.h"
#include "harness/shard_merge.h"
#include "harness/writers.h"
#include "core/error.h"
#include "core/text.h"
#include "tests/error_of.h"
#include "tests/temp_dir.h"

namespace rtbench {
namespace {
namespace fs = std::filesystem;
using ::testing::HasSubstr;

TEST(OutputFolder, ASecondWriterFailsAtOnceNamingTheHoldersPid) {
    TempDir dir;
    const OutputFolderLock first(dir.path().string());
    EXPECT_THAT(errorOf([&] { OutputFolderLock second(dir.path().string()); }),
                HasSubstr("another rtbench process (pid " + std::to_string(::getpid()) +
                          ") is writing this results folder"));
}

TEST(OutputFolder, TheLockEndsWithItsHolder) {
    TempDir dir;
    { const OutputFolderLock first(dir.path().string()); }
    EXPECT_NO_THROW(OutputFolderLock again(dir.path().string()));
}

TEST(OutputFolder, TheExperimentNameIsAPlainFolderName) {
    EXPECT_EQ(experimentFolder("out", "bunny"), "out/bunny");
    for (const std::string& bad :
         std::vector<std::string>{"../../escape", "/tmp/abs", "a/b", "..", ".", "", "x\ny"})
        EXPECT_THAT(errorOf([&] { experimentFolder("out", bad); }),
                    HasSubstr("is not a plain folder name"))
            << bad;
}

TEST(OutputFolder, TheNameIsCheckedWhenTheConfigIsLoaded) {
    TempDir dir;
    const std::string path = dir.write(
        "c.toml",
        "[experiment]\nname = \"../../escape\"\n[scene]\nsource = \"procedural:christen_a\"\n");
    EXPECT_THAT(errorOf([&] { loadExperiment(path); }),
                HasSubstr("c.toml:2: key 'experiment.name': experiment.name '../../escape' is not "
                          "a plain folder name"));
}

TEST(OutputFolder, ARunsCsvThatIsAFolderIsRefusedBeforeAnyRun) {
    TempDir dir;
    fs::create_directories(dir.path() / "out" / "t" / "runs.csv");
    const std::string path =
        dir.write("c.toml", "[experiment]\nname = \"t\"\noutput = \"" + dir.file("out") +
                                "\"\n[scene]\nsource = \"procedural:christen_a\"\n");
    RunnerOptions options;
    options.quiet = true;
    EXPECT_THAT(errorOf([&] { runExperiment(loadExperiment(path), options); }),
                HasSubstr("runs.csv: exists but is not a regular file"));
    EXPECT_FALSE(
        fs::exists(dir.path() / "out" / "t" / "context.json"));  // refused before anything ran
}

TEST(Writers, AFailedWriteLeavesNoTmpAndTheOldFileIntact) {
    TempDir dir;
    const std::string path = dir.write("runs.csv", "old\n");
    // A file-size limit makes the write fail as a full disk would (EFBIG instead of ENOSPC).
    std::signal(SIGXFSZ, SIG_IGN);
    rlimit saved{};
    getrlimit(RLIMIT_FSIZE, &saved);
    rlimit small = saved;
    small.rlim_cur = 64;
    setrlimit(RLIMIT_FSIZE, &small);
    const std::string error = errorOf([&] { writeFileAtomically(path, std::string(100000, 'x')); });
    setrlimit(RLIMIT_FSIZE, &saved);
    EXPECT_THAT(error, HasSubstr("write failed (disk full?)"));
    EXPECT_THAT(error, HasSubstr(path + " is unchanged"));
    for (const auto& entry : fs::directory_iterator(dir.path()))  // no temporary left behind
        EXPECT_EQ(entry.path().filename(), "runs.csv");
    std::ifstream in(path);
    std::string content;
    std::getline(in, content);
    EXPECT_EQ(content, "old");
}

// A held results folder renamed away and replaced by a symlink between two writes (what a check
// before each write cannot close): the writes still go into the folder that was opened, by its
// descriptor, and nothing reaches the link's target.
TEST(OutputFolder, WritesGoIntoTheHeldFolderAfterItIsSwappedForALink) {
    TempDir dir;
    const std::string folder = dir.file("out"), moved = dir.file("moved"), target = dir.file("elsewhere");
    fs::create_directories(folder);
    fs::create_directories(target);
    const FolderIdentity held(folder);
    writeCsv(folder + "/runs.csv", {"run"}, {{{"run", "000"}}});
    fs::rename(folder, moved);
    fs::create_directory_symlink(target, folder);
    writeCsv(folder + "/runs.csv", {"run"}, {{{"run", "000"}}, {{"run", "001"}}});
    appendCsvRow(folder + "/runs.csv", {"run"}, {{"run", "002"}});
    writeFileAtomically(folder + "/context.json", "{}\n");
    EXPECT_TRUE(fs::is_empty(target)) << "a write went through the link";
    EXPECT_EQ(readCsv(moved + "/runs.csv").size(), 3u);
    EXPECT_TRUE(fs::exists(moved + "/context.json"));
    EXPECT_THAT(errorOf([&] { held.check(); }), HasSubstr("symlink"));
}

// check and compare never judge a folder a run is writing: its lock held exclusively names the pid.
TEST(OutputFolder, CheckAndCompareRefuseAFolderBeingWritten) {
    TempDir dir;
    const std::string folder = dir.file("out");
    fs::create_directories(folder);
    {
        const OutputFolderLock lock(folder);
        EXPECT_THAT(errorOf([&] { refuseFolderBeingWritten(folder, "check"); }),
                    HasSubstr("being written by rtbench (pid " + std::to_string(::getpid()) + "): check it when that run ends"));
        EXPECT_THAT(errorOf([&] { compareFolders(folder, folder, {}); }), HasSubstr("compare it when that run ends"));
    }
    EXPECT_EQ(errorOf([&] { refuseFolderBeingWritten(folder, "check"); }), "(no error)");
}

// A written file has the mode open(2) gives a new file: 0666 less the umask.
TEST(Writers, AWrittenFileHasTheModeOfTheUmask) {
    TempDir dir;
    const mode_t saved = ::umask(027);
    writeFileAtomically(dir.file("runs.csv"), "run\n");
    ::umask(saved);
    struct stat st {};
    ASSERT_EQ(::stat(dir.file("runs.csv").c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 0777, 0640u);
}

// merge --missing-as-failed writes its reason into every missing run's error: a control
// character there is refused by name, as in a config string.
TEST(OutputFolder, AMergeReasonWithAControlCharacterIsRefused) {
    TempDir dir;
    EXPECT_THAT(errorOf([&] { mergeShards(dir.path(), std::string("killed\x07 by the scheduler")); }),
                HasSubstr("--missing-as-failed: control character U+0007"));
}

TEST(Writers, ARowWithAnUndeclaredColumnIsAnError) {
    TempDir dir;
    EXPECT_THAT(errorOf([&] {
                    writeCsv(dir.file("r.csv"), {"run", "hits"}, {{{"run", "000"}, {"hitz", "3"}}});
                }),
                HasSubstr("row 1 sets column 'hitz', which is not declared"));
}

TEST(Writers, TextThatIsNotUtf8IsEscaped) {
    EXPECT_EQ(validUtf8("caf\xc3\xa9"), "caf\xc3\xa9");
    EXPECT_EQ(validUtf8("bad\xff\xfe end"), "bad\\xFF\\xFE end");
    EXPECT_EQ(validUtf8("\xc3"), "\\xC3");                    // cut sequence
    EXPECT_EQ(validUtf8("\xc0\xaf"), "\\xC0\\xAF");           // overlong '/'
    EXPECT_EQ(validUtf8("\xed\xa0\x80"), "\\xED\\xA0\\x80");  // surrogate
    TempDir dir;
    writeCsv(dir.file("r.csv"), {"error"}, {{{"error", "mesh says \xff"}}});
    EXPECT_EQ(readCsv(dir.file("r.csv"))[0].at("error"), "mesh says \\xFF");
}

TEST(Writers, QuotedFieldsWithCommasQuotesAndLineBreaksRoundTrip) {
    TempDir dir;
    const Row row = {{"a", "x,y"}, {"b", "say \"hi\""}, {"c", "two\nlines\r\n"}};
    writeCsv(dir.file("r.csv"), {"a", "b", "c"}, {row});
    EXPECT_EQ(readCsv(dir.file("r.csv")).at(0), row);
}

// docs/columns.md documents every column of runs.csv, with the kind `rtbench check` compares it by.
TEST(Columns, TheColumnsPageIsTheDeclaredColumns) {
    std::ifstream in(RTBENCH_SOURCE_DIR "/docs/columns.md");
    std::stringstream text;
    text << in.rdbuf();
    const std::string readme = text.str();
    const std::string begin = "<!-- columns: begin (rtbench columns) -->\n",
                      end = "<!-- columns: end -->";
    const std::size_t from = readme.find(begin), to = readme.find(end);
    ASSERT_NE(from, std::string::npos) << "docs/columns.md has no columns table";
    ASSERT_NE(to, std::string::npos);
    EXPECT_EQ(readme.substr(from + begin.size(), to - from - begin.size()), columnsMarkdown())
        << "docs/columns.md is not the declared columns: scripts/columns_page.py rewrites its table";
}

TEST(Columns, TheCsvHeaderIsEveryConfigKeyThenEveryMetric) {
    const std::vector<std::string> columns = runColumns();
    std::size_t k = 0;
    for (const KeySpec& key : configSchema()) {
        const std::string base = paramColumn(key.name);
        if (key.type == ValueType::Int3 || key.type == ValueType::Float3) {  // three numeric columns (schema 6)
            for (const char* axis : {"_x", "_y", "_z"}) EXPECT_EQ(columns.at(k++), base + axis);
        } else {
            EXPECT_EQ(columns.at(k++), base);
        }
    }
    EXPECT_EQ(columns.at(k), "run");
    for (const char* c : {"camera_position_x", "camera_look_at_z", "scene_translate_y", "camera_up_x"})
        EXPECT_EQ(std::count(columns.begin(), columns.end(), c), 1) << c;
    EXPECT_EQ(std::count(columns.begin(), columns.end(), "camera_position"), 0);
    EXPECT_EQ(columns.back(), "wall_s");
    EXPECT_EQ(std::set<std::string>(columns.begin(), columns.end()).size(),
              columns.size());  // no duplicates
}


// The console's figures: 3 significant digits (0.0185 Mrays/s, not 0.0185003), whole numbers from
// 100 on (6801, not 6.8e+03); text and empty cells as they are.
TEST(Console, FiguresHaveThreeSignificantDigits) {
    EXPECT_EQ(rtbench::consoleNumber("0.0185003"), "0.0185");
    EXPECT_EQ(rtbench::consoleNumber("3.8791"), "3.88");
    EXPECT_EQ(rtbench::consoleNumber("22.1632"), "22.2");
    EXPECT_EQ(rtbench::consoleNumber("6801.4"), "6801");
    EXPECT_EQ(rtbench::consoleNumber("-0.5"), "-0.5");
    EXPECT_EQ(rtbench::consoleNumber("0"), "0");
    EXPECT_EQ(rtbench::consoleNumber("1.5e-07"), "1.5e-07");
    EXPECT_EQ(rtbench::consoleNumber("ok"), "ok");
    EXPECT_EQ(rtbench::consoleNumber(""), "");
    EXPECT_EQ(rtbench::consoleNumber("3.5x"), "3.5x");
}

// What a sweep interrupted by a signal says: how many rows are kept, where, and the command that
// resumes, without --force (which would run the kept rows again).
TEST(Console, TheInterruptNoteNamesTheKeptRowsAndTheResumeCommand) {
    const std::string note = rtbench::interruptNote(3, 17, "out/k/runs.csv", "build/rtbench run --force -q k.toml -f");
    EXPECT_THAT(note, ::testing::HasSubstr("interrupted: 3 of 17 run(s) have their rows in out/k/runs.csv"));
    EXPECT_THAT(note, ::testing::HasSubstr("\n  build/rtbench run -q k.toml\n"));
}

}  // namespace
}  // namespace rtbench
