// The hostile-mesh corpus (tests/corpus/meshes/expected.tsv): every file loads exactly its
// expected triangle count or fails with its expected message, prints nothing on stdout or
// stderr, and takes well under 60 s and 1 GB.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "core/error.h"
#include "scene/mesh_io.h"

namespace rtbench {
namespace {

const std::string kCorpus = RTBENCH_SOURCE_DIR "/tests/corpus/meshes/";

struct CorpusCase {
    std::string file, outcome, expected, note;
};
void PrintTo(const CorpusCase& c, std::ostream* os) {
    *os << c.file;
}

std::vector<CorpusCase> readManifest() {
    std::vector<CorpusCase> cases;
    std::ifstream in(kCorpus + "expected.tsv");
    std::string line;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream fields(line);
        CorpusCase c;
        std::getline(fields, c.file, '\t');
        std::getline(fields, c.outcome, '\t');
        std::getline(fields, c.expected, '\t');
        std::getline(fields, c.note, '\t');
        cases.push_back(c);
    }
    return cases;
}

class Corpus : public ::testing::TestWithParam<CorpusCase> {};

TEST_P(Corpus, Case) {
    const CorpusCase& c = GetParam();
    SCOPED_TRACE(c.file + ": " + c.note);
    ASSERT_TRUE(c.outcome == "triangles" || c.outcome == "error") << "bad manifest line";
    std::string message = "(no error)";
    std::size_t triangles = 0;
    const auto start = std::chrono::steady_clock::now();
    ::testing::internal::CaptureStdout();
    ::testing::internal::CaptureStderr();
    try {
        triangles = readMeshFile(kCorpus + c.file).triangles.size();
    } catch (const Error& e) {
        message = e.what();
    }
    const std::string out = ::testing::internal::GetCapturedStdout();
    const std::string err = ::testing::internal::GetCapturedStderr();
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (c.outcome == "triangles") {
        EXPECT_EQ(message, "(no error)");
        EXPECT_EQ(std::to_string(triangles), c.expected);
    } else {
        EXPECT_THAT(message, ::testing::StartsWith(kCorpus + c.file));
        EXPECT_THAT(message, ::testing::HasSubstr(c.expected));
    }
    EXPECT_EQ(out, "") << "the reader printed on stdout";
    EXPECT_EQ(err, "") << "the reader printed on stderr";
    EXPECT_LT(seconds, 60.0);
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    EXPECT_LT(usage.ru_maxrss, 1L << 20) << "peak memory above 1 GB (ru_maxrss in KiB)";
}

INSTANTIATE_TEST_SUITE_P(Meshes, Corpus, ::testing::ValuesIn(readManifest()),
                         [](const ::testing::TestParamInfo<CorpusCase>& info) {
                             std::string name = info.param.file;
                             for (char& ch : name)
                                 if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                             return name;
                         });

TEST(CorpusManifest, ListsEveryFileOfTheFolder) {
    std::set<std::string> listed;
    for (const CorpusCase& c : readManifest()) EXPECT_TRUE(listed.insert(c.file).second) << c.file;
    std::set<std::string> present;
    for (const auto& entry : std::filesystem::directory_iterator(kCorpus))
        if (const std::string name = entry.path().filename().string();
            name != "expected.tsv" && name != "README.md" && name != "make_corpus.py")
            present.insert(name);
    EXPECT_EQ(listed, present);
    EXPECT_GE(listed.size(), 80u);
}

}  // namespace
}  // namespace rtbench
