// rtbench plan: the runs of a sweep with skip rules, narrowed by --filter, with what earlier rows
// of them took; and the cgal: name suggestions.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "harness/plan_view.h"
#include "scene/mesh_io.h"
#include "tests/error_of.h"
#include "tests/temp_dir.h"

namespace rtbench {
namespace {
using ::testing::HasSubstr;
using ::testing::Not;

const char* kSweep = R"([experiment]
name = "p"
output = "OUT"
[scene]
source = "procedural:christen_a"
[camera]
width = 10
height = 20
[[sweep]]
name = "grid"
structure.type = "uniform_grid"
structure.min_dim = [4, 8, 16]
strategy.type = ["branching", "multipass"]
skip = ["structure.min_dim=16 strategy.type=multipass"]
)";

TEST(Plan, ASweepWithASkipRuleAndFilters) {
    TempDir dir;
    std::string text = kSweep;
    text.replace(text.find("OUT"), 3, dir.file("out"));
    const ExperimentPlan plan = loadExperiment(dir.write("p.toml", text));
    ASSERT_EQ(plan.runs.size(), 5u);  // 3 x 2, one skipped
    EXPECT_EQ(filterRuns(plan, {}).size(), 5u);
    const std::vector<const RunConfig*> multipass = filterRuns(plan, {"strategy.type=multipass"});
    ASSERT_EQ(multipass.size(), 2u);
    EXPECT_EQ(multipass[0]->label(), "grid:structure.min_dim=4 strategy.type=multipass");
    EXPECT_EQ(filterRuns(plan, {"strategy.type=multipass", "structure.min_dim=8"}).size(), 1u);
    EXPECT_EQ(filterRuns(plan, {"min_dim=16"}).size(), 1u);  // text of the label
    EXPECT_TRUE(filterRuns(plan, {"structure.min_dim=5"}).empty());
    EXPECT_THAT(errorOf([&] { filterRuns(plan, {"structure.min_dimm=4"}); }),
                HasSubstr("--filter structure.min_dimm=4: 'structure.min_dimm=4' is not section.key=value for a known key"));
    // Typed as the key's own value, as a skip rule: 45 = 45.000 (the default), a spelling the key refuses is an error.
    EXPECT_EQ(filterRuns(plan, {"camera.fov_deg=45.000"}).size(), 5u);
    EXPECT_THAT(errorOf([&] { filterRuns(plan, {"structure.min_dim=8.5"}); }), HasSubstr("key 'structure.min_dim': expected"));
    EXPECT_THAT(errorOf([&] { filterRuns(plan, {"structure.type=UNIFORM_GRID"}); }), HasSubstr("'UNIFORM_GRID' is not allowed"));
    EXPECT_THAT(errorOf([&] { filterRuns(plan, {""}); }), HasSubstr("an empty filter selects nothing"));

    const std::string table = describePlan(plan, {}, {"strategy.type=branching"});
    EXPECT_THAT(table, HasSubstr("5 runs, 3 selected by --filter -> " + dir.file("out") + "/p/"));
    EXPECT_THAT(table, HasSubstr("swept keys: strategy.type structure.min_dim"));
    EXPECT_THAT(table, HasSubstr("grid:structure.min_dim=16 strategy.type=branching"));
    EXPECT_THAT(table, Not(HasSubstr("strategy.type=multipass")));
    EXPECT_THAT(table, HasSubstr("3 run(s), 600 camera rays in all; no earlier row"));
}

TEST(Plan, NearestNamesPutThoseContainingTheQueryFirst) {
    const std::vector<std::string> names = {"degtri_sliding", "pinion_small", "ChineseDragon-10kv", "dragknob", "bunny00"};
    const std::vector<std::string> nearest = nearestNames("dragon", names, 3);
    ASSERT_EQ(nearest.size(), 3u);
    EXPECT_EQ(nearest[0], "ChineseDragon-10kv");
    EXPECT_EQ(nearest[1], "dragknob");  // edit distance 3
    EXPECT_EQ(nearestNames("bunny", names, 1), std::vector<std::string>{"bunny00"});
}


// The rays column says what the plan knows: the camera rays of primary rays; for rays after the
// first hit, a bound (the batch holds only the rays that continue): the camera rays, times the
// samples per hit of path and ambient-occlusion rays; Whitted's, "~" the camera rays.
TEST(Plan, TheRaysColumnBoundsTheGenerationsAfterTheFirstHit) {
    TempDir dir;
    const ExperimentPlan plan = loadExperiment(dir.write("r.toml", "[experiment]\nname = \"r\"\noutput = \"" + dir.file("out") +
        "\"\n[scene]\nsource = \"procedural:christen_b\"\n[camera]\nwidth = 16\nheight = 12\n[rays]\n"
        "type = [\"primary\", \"shadow\", \"path\", \"ao\", \"whitted\"]\n[path]\nsamples = 2\n[ao]\nsamples = 3\n"));
    const std::string table = describePlan(plan, {}, {});
    EXPECT_THAT(table, ::testing::ContainsRegex("000 +192 +- +rays.type=primary"));
    EXPECT_THAT(table, ::testing::ContainsRegex("001 +<= 192 +- +rays.type=shadow"));
    EXPECT_THAT(table, ::testing::ContainsRegex("002 +<= 384 +- +rays.type=path"));
    EXPECT_THAT(table, ::testing::ContainsRegex("003 +<= 576 +- +rays.type=ao"));
    EXPECT_THAT(table, ::testing::ContainsRegex("004 +~192 +- +rays.type=whitted"));
    EXPECT_THAT(table, HasSubstr("5 run(s), 960 camera rays in all"));
}

}  // namespace
}  // namespace rtbench
