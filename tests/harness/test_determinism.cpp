// Counts are deterministic: every column of kind exact is equal between two runs of one config on
// one device, under every strategy whose work is handed out by atomics or scheduled on the device
// (persistent threads, the scheduled megakernel, multipass with the oracle on the device, the
// wavefront and the path megakernel). A value the device's scheduling decides (the fetch counter's
// overshoot) is of kind scheduled, reported and never compared as a count.
#include <gtest/gtest.h>

#include "harness/columns.h"
#include "tests/harness/test_experiment.h"

namespace rtbench {
namespace {

constexpr const char* kScheduled = R"([scene]
source = "procedural:christen_b"
[camera]
width = 48
height = 40
[structure]
type = ["uniform_grid", "bvh"]
[output]
images = false
[[sweep]]
name = "stream"
strategy.type = ["persistent", "megakernel"]
[[sweep]]
name = "oracle"
strategy.type = "multipass"
strategy.control = "device"
[[sweep]]
name = "paths"
strategy.type = ["wavefront", "path_megakernel"]
rays.type = "path"
path.bounce = 2
)";

TEST(Determinism, EveryExactColumnIsEqualBetweenTwoRunsOfOneConfig) {
    TempDir dir;
    const ExperimentResult first = runTestConfig(dir, "first", kScheduled);
    const ExperimentResult second = runTestConfig(dir, "second", kScheduled);
    ASSERT_EQ(first.rows.size(), 10u);
    ASSERT_EQ(second.rows.size(), first.rows.size());
    int compared = 0;
    for (std::size_t i = 0; i < first.rows.size(); ++i) {
        const Row &a = first.rows[i], &b = second.rows[i];
        ASSERT_EQ(cellText(a, "status"), "ok") << cellText(a, "label") << ": " << cellText(a, "error");
        for (const ColumnSpec& c : runColumnSpecs()) {
            if (c.kind != ColumnKind::Exact) continue;
            EXPECT_EQ(cellText(a, c.name), cellText(b, c.name)) << cellText(a, "label") << ": " << c.name;
            compared += !cellText(a, c.name).empty();
        }
    }
    EXPECT_GT(compared, 400) << "the runs write their counts";
    EXPECT_EQ(columnSpec("rays_fetched").kind, ColumnKind::Scheduled);
}

}  // namespace
}  // namespace rtbench
