// Each config error names the file, line and key, and lists what is allowed.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <set>

#include "harness/config.h"
#include "core/error.h"
#include "core/input_file.h"
#include "tests/error_of.h"
#include "tests/temp_dir.h"

namespace rtbench {
namespace {
using ::testing::HasSubstr;

class Config : public ::testing::Test {
protected:
    std::string write(const std::string& text) { return dir_.write("c.toml", text); }
    std::string errorOf(const std::string& text) {
        try {
            loadExperiment(write(text));
        } catch (const Error& e) {
            return e.what();
        }
        return "(no error)";
    }
    TempDir dir_;
    const std::string path_ = dir_.file("c.toml");
};

const std::string kMinimal = "[experiment]\nname = \"t\"\n[scene]\nsource = \"procedural:christen_a\"\n";

TEST_F(Config, MinimalConfigGetsDefaults) {
    const ExperimentPlan plan = loadExperiment(write(kMinimal));
    ASSERT_EQ(plan.runs.size(), 1u);
    const RunConfig& run = plan.runs[0];
    EXPECT_EQ(run.getInt("camera.width"), 1024);
    EXPECT_EQ(run.getInt("structure.min_dim"), 64);
    EXPECT_FALSE(run.has("structure.resolution"));
    EXPECT_EQ(run.getString("device.name"), "auto");
    EXPECT_EQ(run.getString("strategy.type"), "branching");
    EXPECT_EQ(run.label(), "single run");
}

TEST_F(Config, UnknownKeyNamesFileLineAndAllowedKeys) {
    EXPECT_EQ(errorOf(kMinimal + "[structure]\nmindim = 4\n"),
              path_ + ":6: unknown key 'structure.mindim' (allowed in [structure]: type, min_dim, resolution, "
                      "cells_per_triangle, conservative, leaf_size, quality, max_tests); did you mean 'structure.min_dim'?");
}

TEST_F(Config, UnknownSection) {
    EXPECT_THAT(errorOf(kMinimal + "\n[strategies]\ntype = \"x\"\n"),
                HasSubstr(path_ + ":6: unknown section [strategies] (allowed: experiment, scene, camera, structure, "
                                  "strategy, cache, rays, light, reflection, refraction, path, ao, whitted, intersection, baseline, accuracy, device, output, sweep)"));
}

TEST_F(Config, VertexBitsArePackedWidthsOrFloat) {
    EXPECT_EQ(loadExperiment(write(kMinimal + "[intersection]\nvertex_bits = [32, 16, 1]\n")).runs.size(), 3u);
    EXPECT_EQ(errorOf(kMinimal + "[intersection]\nvertex_bits = 20\n"),
              path_ + ":6: key 'intersection.vertex_bits': value 20 is not allowed (allowed: 1, 2, 3, 4, 5, 6, 7, 8, 9, "
                      "10, 11, 12, 13, 14, 15, 16, 32)");
}

TEST_F(Config, OneSimplificationTarget) {
    EXPECT_EQ(errorOf(kMinimal + "simplify_ratio = 0.5\nsimplify_triangles = 10\n"),
              path_ + ":6: keys scene.simplify_ratio and scene.simplify_triangles both set the scene simplification; give exactly one");
}

TEST_F(Config, WrongType) {
    EXPECT_EQ(errorOf(kMinimal + "[camera]\nwidth = \"wide\"\n"),
              path_ + ":6: key 'camera.width': expected an integer (or a list of them to sweep)");
    EXPECT_EQ(errorOf(kMinimal + "[structure]\nresolution = [1, 2]\n"),
              path_ + ":6: key 'structure.resolution': expected an array of 3 integers (or a list of them to sweep)");
}

TEST_F(Config, OutOfRange) {
    EXPECT_EQ(errorOf(kMinimal + "[structure]\nmin_dim = 0\n"),
              path_ + ":6: key 'structure.min_dim': value 0 is out of range [1, 2048]");
    EXPECT_EQ(errorOf(kMinimal + "[camera]\nwidth = [64, -1]\n"),
              path_ + ":6: key 'camera.width': value -1 is out of range [1, 16384]");
    // The upper bounds too, for integers, numbers and each component of a 3-vector.
    EXPECT_EQ(errorOf(kMinimal + "[camera]\nheight = 16385\n"),
              path_ + ":6: key 'camera.height': value 16385 is out of range [1, 16384]");
    EXPECT_EQ(errorOf(kMinimal + "[camera]\nfov_deg = 180.0\n"),
              path_ + ":6: key 'camera.fov_deg': value 180 is out of range [1, 179]");
    EXPECT_EQ(errorOf(kMinimal + "[structure]\nresolution = [8, 4097, 8]\n"),
              path_ + ":6: key 'structure.resolution': value 4097 is out of range [1, 4096]");
}

TEST_F(Config, ValueNotInTheAllowedSet) {
    EXPECT_EQ(errorOf(kMinimal + "[strategy]\ntype = \"ray_sorting\"\n"),
              path_ + ":6: key 'strategy.type': 'ray_sorting' is not allowed (allowed: branching, multipass, persistent, megakernel, ray_query, plain, cpu, wavefront, path_megakernel, control, sorted)");
}

TEST_F(Config, MissingRequiredKey) {
    EXPECT_THAT(errorOf("[experiment]\nname = \"t\"\n"), HasSubstr(path_ + ": missing required key 'scene.source'"));
}

TEST_F(Config, TwoResolutionRules) {
    EXPECT_EQ(errorOf(kMinimal + "[structure]\nmin_dim = 8\nresolution = [4, 4, 4]\n"),
              path_ + ":7: keys structure.min_dim and structure.resolution both set the grid resolution; give exactly one");
}

TEST_F(Config, SyntaxErrorNamesTheLine) {
    EXPECT_THAT(errorOf(kMinimal + "[camera]\nwidth = = 3\n"), HasSubstr(path_ + ":6: TOML syntax error"));
}

TEST_F(Config, MissingFile) {
    try {
        loadExperiment(dir_.file("absent.toml"));
        FAIL();
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), dir_.file("absent.toml") + ": config file not found");
    }
}

TEST_F(Config, ListValuedKeysExpandToTheCartesianProduct) {
    const ExperimentPlan plan = loadExperiment(
        write(kMinimal + "[camera]\nwidth = [32, 64]\n[structure]\nresolution = [[1, 2, 3], [4, 5, 6], [7, 8, 9]]\n"));
    ASSERT_EQ(plan.runs.size(), 6u);
    EXPECT_EQ(plan.runs[0].getInt("camera.width"), 32);
    EXPECT_EQ(plan.runs[0].getVec3("structure.resolution"), (std::array<double, 3>{1, 2, 3}));
    EXPECT_EQ(plan.runs[1].getVec3("structure.resolution"), (std::array<double, 3>{4, 5, 6}));
    EXPECT_EQ(plan.runs[3].getInt("camera.width"), 64);
    EXPECT_EQ(plan.runs[5].label(), "camera.width=64 structure.resolution=[7 8 9]");
    EXPECT_NE(plan.runs[0].hash(), plan.runs[1].hash());
    EXPECT_EQ(plan.runs[0].hash(), loadExperiment(path_).runs[0].hash());  // stable
}

TEST_F(Config, EmptyListIsAnError) {
    EXPECT_EQ(errorOf(kMinimal + "[structure]\nmin_dim = []\n"),
              path_ + ":6: key 'structure.min_dim': an empty list sweeps nothing");
}

}  // namespace
}  // namespace rtbench

namespace rtbench {
namespace {

TEST_F(Config, AKeyNoRunReadsIsAnError) {
    EXPECT_EQ(errorOf(kMinimal + "[strategy]\ntype = \"branching\"\ntraverse_steps_per_pass = 4\n"),
              path_ + ":7: key 'strategy.traverse_steps_per_pass' is never read: it applies only when "
                      "strategy.type=multipass");
    EXPECT_EQ(errorOf(kMinimal + "[strategy]\ntype = \"multipass\"\nscheduling = \"naive\"\noracle_threshold = 0.5\n"),
              path_ + ":8: key 'strategy.oracle_threshold' is never read: it applies only when "
                      "strategy.type=multipass and strategy.scheduling=oracle");
}

// The registry (methods/registry.cpp) gives structure.type its values and each structure its keys.
TEST_F(Config, AnUnknownStructureListsTheKnownOnesAndAStructuresKeyGivenToAnotherIsNamed) {
    EXPECT_EQ(errorOf(kMinimal + "[structure]\ntype = \"octree\"\n"),
              path_ + ":6: key 'structure.type': 'octree' is not allowed (allowed: uniform_grid, bvh, brute_force, auto, driver, median_bvh)");
    EXPECT_EQ(errorOf(kMinimal + "[structure]\ntype = \"uniform_grid\"\nleaf_size = 8\n"),
              path_ + ":7: key 'structure.leaf_size' is never read: it applies only when structure.type=bvh|median_bvh");
    EXPECT_EQ(errorOf(kMinimal + "[structure]\ntype = \"bvh\"\nmin_dim = 8\n"),
              path_ + ":7: key 'structure.min_dim' is never read: it applies only when structure.type=uniform_grid");
    // A sweep over structures gives each its own keys only.
    const ExperimentPlan plan = loadExperiment(
        write(kMinimal + "[structure]\ntype = [\"uniform_grid\", \"bvh\", \"brute_force\"]\nmin_dim = 8\nleaf_size = [2, 8]\n"));
    ASSERT_EQ(plan.runs.size(), 4u);
    EXPECT_TRUE(plan.runs[0].has("structure.min_dim"));
    EXPECT_FALSE(plan.runs[0].has("structure.leaf_size"));
    EXPECT_EQ(plan.runs[2].getInt("structure.leaf_size"), 8);
    EXPECT_FALSE(plan.runs[3].has("structure.min_dim"));
    EXPECT_TRUE(plan.runs[3].has("structure.max_tests"));
}

TEST_F(Config, KeysForOneStrategyAreDroppedFromTheOthersRunsWithoutDuplicates) {
    const ExperimentPlan plan = loadExperiment(
        write(kMinimal + "[strategy]\ntype = [\"branching\", \"multipass\"]\ntraverse_steps_per_pass = [1, 4]\n"));
    ASSERT_EQ(plan.runs.size(), 3u);  // branching once, multipass with K = 1 and 4
    EXPECT_EQ(plan.runs[0].getString("strategy.type"), "branching");
    EXPECT_FALSE(plan.runs[0].has("strategy.traverse_steps_per_pass"));
    EXPECT_EQ(plan.runs[0].label(), "strategy.type=branching");
    EXPECT_EQ(plan.runs[2].getInt("strategy.traverse_steps_per_pass"), 4);
    EXPECT_EQ(plan.runs[2].index, 2u);
}

TEST_F(Config, SweepsAreTheUnionOfTheirProductsOverTheBaseValues) {
    const ExperimentPlan plan = loadExperiment(write(kMinimal + R"(
[structure]
min_dim = 16
[strategy]
type = "multipass"

[[sweep]]
name = "oracle"
strategy.oracle_threshold = [0.0, 1.0]

[[sweep]]
name = "grid"
structure.resolution = [[4, 4, 4], [8, 8, 8]]
strategy.type = ["branching", "multipass"]
)"));
    ASSERT_EQ(plan.runs.size(), 6u);
    EXPECT_EQ(plan.runs[0].sweep, "oracle");
    EXPECT_EQ(plan.runs[0].getInt("structure.min_dim"), 16);
    EXPECT_EQ(plan.runs[1].getFloat("strategy.oracle_threshold"), 1.0);
    EXPECT_EQ(plan.runs[1].label(), "oracle:strategy.oracle_threshold=1");
    EXPECT_EQ(plan.runs[2].sweep, "grid");
    EXPECT_FALSE(plan.runs[2].has("structure.min_dim"));  // the sweep's rule replaces the base's
    EXPECT_EQ(plan.runs[5].getVec3("structure.resolution"), (std::array<double, 3>{8, 8, 8}));
    EXPECT_EQ(plan.runs[5].getString("strategy.type"), "multipass");
}

TEST_F(Config, UnknownKeyInASweep) {
    EXPECT_EQ(errorOf(kMinimal + "[[sweep]]\nstrategy.kk = [1, 2]\n"),
              path_ + ":6: unknown key 'strategy.kk' (allowed in [strategy]: type, workgroup_size, "
                      "traverse_steps_per_pass, intersections_per_pass, suppress_finished_reads, scheduling, "
                      "oracle_threshold, oracle_basis, max_passes, control, list_partitions, batch_rays, persistent_workgroups, rays_per_fetch, schedule, threads)");
}

}  // namespace
}  // namespace rtbench

namespace rtbench {
namespace {

TEST_F(Config, SkipRulesLeaveOutInvalidCombinations) {
    const ExperimentPlan plan = loadExperiment(write(kMinimal + R"(
[strategy]
type = "multipass"

[[sweep]]
name = "unroll"
strategy.traverse_steps_per_pass = [1, 2]
strategy.intersections_per_pass = [1, 2]
strategy.suppress_finished_reads = [false, true]
skip = ["strategy.traverse_steps_per_pass=1 strategy.intersections_per_pass=1 strategy.suppress_finished_reads=true"]
)"));
    ASSERT_EQ(plan.runs.size(), 7u);  // 8 combinations, one with nothing to suppress
    for (const RunConfig& run : plan.runs)
        EXPECT_FALSE(run.getInt("strategy.traverse_steps_per_pass") == 1 && run.getInt("strategy.intersections_per_pass") == 1 &&
                     run.getBool("strategy.suppress_finished_reads"));
    EXPECT_EQ(errorOf(kMinimal + "[[sweep]]\nskip = [\"strategy.kk=1\"]\n"),
              path_ + ":6: key 'sweep.skip': 'strategy.kk=1' is not section.key=value for a known key");
}

TEST_F(Config, ASweepWhoseEveryRunIsSkippedIsAnErrorNamingIt) {
    EXPECT_EQ(errorOf(kMinimal + "[[sweep]]\nname = \"all\"\nskip = [\"device.name=auto\"]\n" +
                      "[sweep.camera]\nheight = [8, 16]\n"),
              path_ + ":5: every one of the 2 runs of sweep 'all' matches a skip rule: the sweep runs nothing");
}

TEST_F(Config, TheEmbreeConfigIsCheckedBeforeEmbreeSeesIt) {
    const std::string base = kMinimal + "[baseline]\nembree_config = ";
    EXPECT_EQ(errorOf(base + "\"isa=bogus,threads=-5\"\n"),
              path_ + ":6: key 'baseline.embree_config': isa=bogus: unknown ISA (allowed: sse2, sse4.2, avx, avx2, avx512)");
    EXPECT_EQ(errorOf(base + "\"threads=-5\"\n"),
              path_ + ":6: key 'baseline.embree_config': threads=-5: expected an integer >= 0 (0: all)");
    EXPECT_EQ(errorOf(base + "\"isa\"\n"),
              path_ + ":6: key 'baseline.embree_config': 'isa' is not key=value (e.g. \"isa=avx2,threads=2\")");
    EXPECT_THAT(errorOf(base + "\"tesselation=3\"\n"), HasSubstr("unknown Embree config key 'tesselation'"));
    EXPECT_NO_THROW(loadExperiment(write(base + "\"isa=sse2,threads=2\"\n")));
}

}  // namespace
}  // namespace rtbench

namespace rtbench {
namespace {

// Skip rules compare typed values: a rule cannot miss a run by how a number is spelled, a choice
// that does not exist is named, and a rule that matches no run is an error naming it.
TEST_F(Config, SkipRulesCompareTypedValues) {
    const std::string sweep = kMinimal + "[camera]\nfov_deg = [30.0, 40]\n[[sweep]]\nskip = [\"";
    for (const std::string rule : {"camera.fov_deg=30.000", "camera.fov_deg=30", "camera.fov_deg=3e1"}) {
        const ExperimentPlan plan = loadExperiment(write(sweep + rule + "\"]\n"));
        ASSERT_EQ(plan.runs.size(), 1u) << rule;
        EXPECT_EQ(plan.runs[0].getFloat("camera.fov_deg"), 40.0) << rule;
    }
    EXPECT_EQ(loadExperiment(write(kMinimal + "[camera]\nfov_deg = [30.5, 40]\n[[sweep]]\nskip = [\"camera.fov_deg=30.50\"]\n"))
                  .runs.size(),
              1u);
    // A vector value, written as TOML writes it.
    EXPECT_EQ(loadExperiment(write(kMinimal + "[camera]\nup = [[1, 0, 0], [0, 1, 0]]\n[[sweep]]\nskip = [\"camera.up=[1, 0, 0]\"]\n"))
                  .runs.size(),
              1u);
    EXPECT_THAT(errorOf(kMinimal + "[camera]\nup = [[1, 0, 0], [0, 1, 0]]\n[[sweep]]\nskip = [\"camera.up=[1 0 0]\"]\n"),
                HasSubstr("'[1 0 0]' is not an array of 3 numbers"));
    // Checked as the key would be.
    EXPECT_THAT(errorOf(kMinimal + "[structure]\nconservative = [true, false]\n[[sweep]]\nskip = [\"structure.conservative=1\"]\n"),
                HasSubstr("key 'structure.conservative': expected true or false"));
    EXPECT_THAT(errorOf(kMinimal + "[structure]\ntype = [\"bvh\", \"uniform_grid\"]\n[[sweep]]\nskip = [\"structure.type=BVH\"]\n"),
                HasSubstr("'BVH' is not allowed (allowed: uniform_grid, bvh, brute_force, auto, driver, median_bvh)"));
    EXPECT_EQ(loadExperiment(write(kMinimal + "[structure]\ntype = \"brute_force\"\nmax_tests = [1e9, 2e9]\n[[sweep]]\nskip = [\"structure.max_tests=1000000000\"]\n"))
                  .runs.size(),
              1u);
    // One value, nothing after it: a comment would hide what follows.
    EXPECT_THAT(errorOf(kMinimal + "scale = [1, 2]\n[[sweep]]\nskip = [\"scene.scale=2#junk\"]\n"),
                HasSubstr("'2#junk' is not a number"));
    // A rule that matches nothing is a typo or a value the sweep never takes.
    EXPECT_THAT(errorOf(kMinimal + "[camera]\nfov_deg = [30, 40]\n[[sweep]]\nskip = [\"camera.fov_deg=35\"]\n"),
                HasSubstr(path_ + ":8: key 'sweep.skip': the rule \"camera.fov_deg=35\" matches no run of this sweep"));
}

// A skip condition on a key only some runs read (leaf_size: the BVH's) matches only those runs.
TEST_F(Config, ASkipRuleOnAKeySomeRunsLackSkipsOnlyRunsThatHaveIt) {
    const ExperimentPlan plan = loadExperiment(write(
        kMinimal + "[structure]\ntype = [\"bvh\", \"uniform_grid\"]\nleaf_size = [2, 8]\n[[sweep]]\nskip = [\"structure.leaf_size=8\"]\n"));
    ASSERT_EQ(plan.runs.size(), 2u);  // bvh leaf 2, and the grid (which has no leaf_size)
    EXPECT_EQ(plan.runs[0].getInt("structure.leaf_size"), 2);
    EXPECT_EQ(plan.runs[1].getString("structure.type"), "uniform_grid");
}

TEST_F(Config, KeysThatPlaceTheResultsAreNotSweepable) {
    EXPECT_THAT(errorOf("[experiment]\nname = [\"a\", \"b\"]\n[scene]\nsource = \"procedural:christen_a\"\n"),
                HasSubstr(path_ + ":2: key 'experiment.name': places the results and cannot be swept"));
    EXPECT_THAT(errorOf("[experiment]\nname = \"a\"\noutput = [\"x\", \"y\"]\n[scene]\nsource = \"procedural:christen_a\"\n"),
                HasSubstr("key 'experiment.output': places the results and cannot be swept"));
    EXPECT_THAT(errorOf(kMinimal + "[[sweep]]\nexperiment.name = \"b\"\n"),
                HasSubstr("key 'experiment.name' places the results: set it once, outside [[sweep]] tables"));
}

// NUL and other control characters are refused in every string (a NUL would cut a path where the
// OS reads it, and the messages quoting it).
TEST_F(Config, ControlCharactersInStringsAreRefused) {
    EXPECT_THAT(errorOf("[experiment]\nname = \"t\"\n[scene]\nsource = \"flat.off\\u0000zzz.off\"\n"),
                HasSubstr(path_ + ":4: key 'scene.source': control character U+0000 at byte 8"));
    EXPECT_THAT(errorOf(kMinimal + "[device]\nname = \"llvm\\tpipe\"\n"), HasSubstr("control character U+0009"));
    EXPECT_THAT(errorOf(kMinimal + "[[sweep]]\nname = \"a\\u001bb\"\n"), HasSubstr("key 'sweep.name': control character U+001B"));
}

// A list of three numbers for scene.scale could be a sweep or a per-axis scale (as a scene
// description reads it): refused, saying which is which.
TEST_F(Config, ThreeScalesAreAmbiguousAndSaySo) {
    EXPECT_THAT(errorOf(kMinimal + "scale = [1, 2, 3]\n"), HasSubstr("key 'scene.scale': a list of 3 numbers is ambiguous"));
    EXPECT_EQ(loadExperiment(write(kMinimal + "scale = [1, 2]\n")).runs.size(), 2u);
    EXPECT_EQ(loadExperiment(write(kMinimal + "scale = [1, 2, 3, 4]\n")).runs.size(), 4u);
}

TEST_F(Config, ARangeErrorQuotesTheValueAsWritten) {
    EXPECT_EQ(errorOf(kMinimal + "[camera]\nfov_deg = 179.9999\n"),
              path_ + ":6: key 'camera.fov_deg': value 179.9999 is out of range [1, 179]");
}

// The config file must be a regular file within the size limit: a FIFO would hang, /dev/zero
// read until memory runs out, a folder is not a config.
TEST_F(Config, OnlyARegularConfigFileOfBoundedSizeIsRead) {
    std::filesystem::create_directory(dir_.path() / "folder.toml");
    EXPECT_THAT(rtbench::errorOf([&] { loadExperiment(dir_.file("folder.toml")); }),
                HasSubstr("folder.toml: the config file is a folder, not a regular file"));
    ASSERT_EQ(::mkfifo(dir_.file("fifo.toml").c_str(), 0644), 0);
    EXPECT_THAT(rtbench::errorOf([&] { loadExperiment(dir_.file("fifo.toml")); }),
                HasSubstr("fifo.toml: the config file is a FIFO, not a regular file"));
    std::filesystem::create_symlink("/dev/zero", dir_.path() / "zero.toml");
    EXPECT_THAT(rtbench::errorOf([&] { loadExperiment(dir_.file("zero.toml")); }),
                HasSubstr("zero.toml: the config file is a character device, not a regular file"));
    dir_.write("big.toml", std::string(kMaxConfigBytes + 1, '#'));
    EXPECT_THAT(rtbench::errorOf([&] { loadExperiment(dir_.file("big.toml")); }),
                HasSubstr("big.toml: the config file is 4194305 bytes, over the limit of 4 MiB"));
    std::filesystem::create_symlink("loop.toml", dir_.path() / "loop.toml");
    EXPECT_THAT(rtbench::errorOf([&] { loadExperiment(dir_.file("loop.toml")); }), HasSubstr("loop.toml: config file is a symlink loop"));
}

}  // namespace
}  // namespace rtbench

// --set "section.key=value": the key replaced wherever the file sets it (base, every [[sweep]], the
// other keys of its group), the value read as TOML (a list sweeps) or as a bare string, checked as
// the file's keys are, with errors that name the --set.
namespace rtbench {
namespace {
using ::testing::HasSubstr;

class Settings : public ::testing::Test {
protected:
    ExperimentPlan load(const std::string& text, const std::vector<std::string>& settings) {
        return loadExperiment(dir_.write("s.toml", text), settings);
    }
    std::string errorOf(const std::string& text, const std::vector<std::string>& settings) {
        try {
            load(text, settings);
        } catch (const Error& e) {
            return e.what();
        }
        return "(no error)";
    }
    TempDir dir_;
};

const std::string kGridSweep = "[experiment]\nname = \"s\"\n[scene]\nsource = \"procedural:christen_a\"\n"
                               "[structure]\ncells_per_triangle = 2.0\n[[sweep]]\nname = \"a\"\nstructure.min_dim = 4\n"
                               "[[sweep]]\nname = \"b\"\ncamera.width = 32\n";

// Three mistakes, one report: each with its file, line and key, and the nearest name for typos.
TEST_F(Config, EveryErrorOfTheFileIsReportedAtOnce) {
    const std::string error = errorOf("[experiment]\nname = \"t\"\nrepetitons = 3\n[scene]\nsource = \"procedural:christen_a\"\n"
                                      "[camera]\nwidth = \"wide\"\n[strategy]\ntype = \"multipas\"\n");
    EXPECT_THAT(error, HasSubstr("3 errors in " + path_ + ":\n"));
    EXPECT_THAT(error, HasSubstr(path_ + ":3: unknown key 'experiment.repetitons'"));
    EXPECT_THAT(error, HasSubstr("did you mean 'experiment.repetitions'?"));
    EXPECT_THAT(error, HasSubstr(path_ + ":7: key 'camera.width': expected an integer"));
    EXPECT_THAT(error, HasSubstr(path_ + ":9: key 'strategy.type': 'multipas' is not allowed"));
    EXPECT_THAT(error, HasSubstr("did you mean 'multipass'?"));
    // One mistake reads as before: the error alone.
    EXPECT_THAT(errorOf(kMinimal + "[camera]\nwidth = \"wide\"\n"), ::testing::StartsWith(path_ + ":6: key 'camera.width'"));
}

TEST_F(Settings, AListSweepsAndReplacesTheKeyInEverySweepAndItsGroup) {
    const ExperimentPlan plan = load(kGridSweep, {"structure.min_dim=[8, 16]"});
    ASSERT_EQ(plan.runs.size(), 4u);  // 2 sweeps x 2 values
    std::multiset<std::int64_t> dims;
    for (const RunConfig& run : plan.runs) {
        dims.insert(run.getInt("structure.min_dim"));
        EXPECT_FALSE(run.has("structure.cells_per_triangle")) << "the other key of min_dim's group is replaced";
    }
    EXPECT_EQ(dims, (std::multiset<std::int64_t>{8, 8, 16, 16}));
    EXPECT_EQ(plan.settings, std::vector<std::string>{"structure.min_dim=[8, 16]"});
    // The runs' hashes (their identity) follow the setting.
    const ExperimentPlan other = load(kGridSweep, {"structure.min_dim=[8, 32]"});
    EXPECT_EQ(plan.runs[0].hash(), other.runs[0].hash());
    EXPECT_NE(plan.runs[1].hash(), other.runs[1].hash());
}

TEST_F(Settings, ABareWordIsAStringAndAQuotedOneToo) {
    for (const std::string& setting : {std::string("scene.source=procedural:christen_b"),
                                       std::string("scene.source=\"procedural:christen_b\"")}) {
        const ExperimentPlan plan = load(kMinimal, {setting});
        ASSERT_EQ(plan.runs.size(), 1u);
        EXPECT_EQ(plan.runs[0].getString("scene.source"), "procedural:christen_b") << setting;
    }
}

TEST_F(Settings, ErrorsNameTheSetting) {
    EXPECT_THAT(errorOf(kMinimal, {"structure.min_dimm=4"}),
                HasSubstr("--set structure.min_dimm=4: unknown key 'structure.min_dimm' (nearest: structure.min_dim"));
    EXPECT_THAT(errorOf(kMinimal, {"structure.min_dim=abc"}), HasSubstr("--set structure.min_dim=abc: "));
    EXPECT_THAT(errorOf(kMinimal, {"structure.min_dim=abc"}), HasSubstr("expected an integer"));
    EXPECT_THAT(errorOf(kMinimal, {"experiment.repetitions=0"}), HasSubstr("--set experiment.repetitions=0: "));
    EXPECT_THAT(errorOf(kMinimal, {"min_dim"}), HasSubstr("--set min_dim: expected section.key=value"));
    // A value that is two TOML keys is not one value: read as a string, then refused by type.
    EXPECT_THAT(errorOf(kMinimal, {"structure.min_dim=4\nexperiment.name = \"x\""}), HasSubstr("expected an integer"));
}

}  // namespace
}  // namespace rtbench
