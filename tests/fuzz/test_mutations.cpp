// A short fuzz run in every CI run: the libFuzzer targets' bodies (fuzz/fuzz_bodies.h) on seeds
// mutated as libFuzzer mutates (byte flips, inserted dictionary tokens, cut, doubled and spliced
// ranges), from a fixed seed so that a finding reproduces. The sanitizer half of CI runs it under
// ASan and UBSan; scripts/fuzz.sh fuzzes the same bodies with coverage guidance for as long as asked.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "fuzz/fuzz_bodies.h"
#include "core/input_file.h"
#include "tests/temp_dir.h"

namespace rtbench {
namespace {
namespace fs = std::filesystem;

std::string sourceFile(const std::string& relative) {
    return readInputFile((fs::path(RTBENCH_SOURCE_DIR) / relative).string(), std::size_t(1) << 24, "seed");
}

// Every file of a folder of the source tree, each prefixed by `prefix` (the byte that picks a reader).
std::vector<std::string> seedsIn(const std::string& folder, const std::function<std::string(const std::string&)>& prefix) {
    std::vector<std::string> paths, seeds;
    for (const auto& entry : fs::directory_iterator(fs::path(RTBENCH_SOURCE_DIR) / folder)) paths.push_back(entry.path().string());
    std::sort(paths.begin(), paths.end());
    for (const std::string& path : paths) seeds.push_back(prefix(path) + readInputFile(path, std::size_t(1) << 24, "seed"));
    return seeds;
}

// A libFuzzer dictionary's tokens ("..." per line, \xNN and \" escapes).
std::vector<std::string> dictionary(const std::string& relative) {
    std::vector<std::string> tokens;
    std::string line;
    std::istringstream in(sourceFile(relative));
    while (std::getline(in, line)) {
        const std::size_t open = line.find('"'), close = line.rfind('"');
        if (line.empty() || line[0] == '#' || open == std::string::npos || close <= open) continue;
        std::string token;
        for (std::size_t i = open + 1; i < close; ++i) {
            if (line[i] == '\\' && i + 1 < close && line[i + 1] == 'x' && i + 3 < close) {
                token += char(std::stoi(line.substr(i + 2, 2), nullptr, 16));
                i += 3;
            } else if (line[i] == '\\' && i + 1 < close) {
                token += line[++i];
            } else {
                token += line[i];
            }
        }
        tokens.push_back(token);
    }
    return tokens;
}

// One to four of libFuzzer's mutations of a seed.
std::string mutate(std::string s, const std::vector<std::string>& seeds, const std::vector<std::string>& tokens, std::mt19937& rng) {
    auto below = [&](std::size_t n) { return n ? std::size_t(rng() % n) : 0; };
    const int count = 1 + int(rng() % 4);
    for (int m = 0; m < count; ++m) {
        const std::size_t at = below(s.size() + 1), length = 1 + below(std::min<std::size_t>(64, s.size() + 1));
        switch (rng() % 6) {
            case 0: if (!s.empty()) s[std::min(at, s.size() - 1)] ^= char(1u << (rng() % 8)); break;      // flip a bit
            case 1: s.insert(at, tokens[below(tokens.size())]); break;                                       // a token
            case 2: s.erase(at, length); break;                                                              // cut
            case 3: s.insert(at, s.substr(below(s.size()), length)); break;                                  // double a range
            case 4: { const std::string& other = seeds[below(seeds.size())];                                 // splice
                      s = s.substr(0, at) + other.substr(below(other.size())); break; }
            default: s.insert(at, 1, char(rng() % 256)); break;                                              // a byte
        }
    }
    return s;
}

// `iterations` mutated inputs through `body`; every finding named with the input that made it.
void fuzzBriefly(const std::vector<std::string>& seeds, const std::vector<std::string>& tokens, int iterations,
                 const std::function<std::string(const std::string&)>& body) {
    ASSERT_FALSE(seeds.empty());
    for (const std::string& seed : seeds) ASSERT_EQ(body(seed), "") << "a seed is a finding";
    std::mt19937 rng(20261206u);
    int findings = 0;
    for (int i = 0; i < iterations && findings < 5; ++i) {
        const std::string input = mutate(seeds[i % seeds.size()], seeds, tokens, rng);
        const std::string problem = body(input);
        if (problem.empty()) continue;
        ++findings;
        ADD_FAILURE() << "iteration " << i << ": " << problem << "\ninput (" << input.size() << " bytes, first 400):\n"
                      << input.substr(0, 400);
    }
}

TEST(FuzzBriefly, MeshReadersReturnAValidMeshOrAnError) {
    const auto seeds = seedsIn("fuzz/seeds/fuzz_mesh", [](const std::string& path) {
        const std::string ext = fs::path(path).extension().string();
        return std::string(1, ext == ".off" ? '0' : ext == ".obj" ? '1' : ext == ".ply" ? '2' : '3');
    });
    fuzzBriefly(seeds, dictionary("fuzz/fuzz_mesh.dict"), 40000, [](const std::string& in) { return fuzz::meshInput(in); });
}

TEST(FuzzBriefly, ConfigsBecomeAPlanOrAnError) {
    auto seeds = seedsIn("fuzz/seeds/fuzz_config", [](const std::string&) { return std::string(); });
    seeds.push_back(sourceFile("configs/first.toml"));
    fuzzBriefly(seeds, dictionary("fuzz/fuzz_config.dict"), 15000, [](const std::string& in) { return fuzz::configInput(in); });
}

TEST(FuzzBriefly, ResultsFilesAreReadOrRefused) {
    const std::vector<std::string> seeds = {"0" + sourceFile("results/golden/runs.csv"), "1" + sourceFile("results/golden/samples.csv"),
                                            "2" + sourceFile("results/golden/context.json")};
    fuzzBriefly(seeds, dictionary("fuzz/fuzz_results.dict"), 3000, [](const std::string& in) { return fuzz::resultsInput(in); });
}

TEST(FuzzBriefly, SceneDescriptionsPlaceMeshesOrAreRefused) {
    TempDir dir;
    const std::string folder = dir.file("scene");
    fs::create_directories(folder);
    const auto seeds = seedsIn("fuzz/seeds/fuzz_scene", [](const std::string&) { return std::string(); });
    fuzzBriefly(seeds, dictionary("fuzz/fuzz_config.dict"), 6000,
                [&](const std::string& in) { return fuzz::sceneInput(in, folder); });
}

}  // namespace
}  // namespace rtbench
