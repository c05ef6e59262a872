// camera.tile (Purcell 2002 §5.3's tiled rendering): the tile order by hand, and a tiled run whose
// records, checks and images are the untiled run's while its memory references come in tiles.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "rays/primary/tile_order.h"
#include "tests/error_of.h"
#include "tests/harness/test_experiment.h"

namespace rtbench {
namespace {

using ::testing::HasSubstr;

TEST(TileOrder, WalksTilesRowByRowAndEachTileRowByRow) {
    // A 6 x 4 image in tiles of 2: pixel y * 6 + x.
    EXPECT_EQ(tileOrder(6, 4, 2), (std::vector<std::uint32_t>{0, 1, 6, 7, 2, 3, 8, 9, 4, 5, 10, 11,  //
                                                              12, 13, 18, 19, 14, 15, 20, 21, 16, 17, 22, 23}));
    EXPECT_TRUE(tileOrder(6, 4, 0).empty());
    EXPECT_EQ(tileOrder(6, 4, 1).size(), 24u);
    EXPECT_THAT(errorOf([] { tileOrder(6, 4, 4); }), HasSubstr("camera.tile = 4: the image (6 x 4) is not a whole number of tiles"));
    // The records come back where their rays were.
    RayBatch batch;
    for (int i = 0; i < 24; ++i) batch.rays.push_back({glm::vec4(float(i), 0, 0, 0), glm::vec4(0, 0, 1, 1)});
    const std::vector<std::uint32_t> order = tileOrder(6, 4, 2);
    const RayBatch tiled = inOrder(batch, order);
    std::vector<gpu::HitRecord> records(24);
    for (int i = 0; i < 24; ++i) records[i].t = tiled.rays[i].originTMin.x;  // a record made from its ray
    const std::vector<gpu::HitRecord> back = inBatchOrder(records, order);
    for (int i = 0; i < 24; ++i) EXPECT_EQ(back[i].t, float(i));
}

// The same rays in tiles: every record and count the same for branching; multipass with a batch
// per tile renders each to completion (its passes add up over the tiles); the cache replay sees
// the tiles' order.
TEST(TileOrder, ATiledRunHasTheUntiledRunsRecords) {
    TempDir dir;
    const auto config = [](const std::string& camera, const std::string& rest) {
        return "[scene]\nsource = \"procedural:christen_b\"\n[camera]\nwidth = 32\nheight = 24\n" + camera +
               "[structure]\nmin_dim = 8\n[cache]\nsimulate = true\nsize_bytes = 4096\n[output]\nimages = false\n" + rest;
    };
    const ExperimentResult result = runTestConfig(
        dir, "tiles", config("tile = [0, 8]\n", "[strategy]\ntype = [\"branching\", \"multipass\"]\nbatch_rays = 64\n"));
    ASSERT_EQ(result.rows.size(), 4u);
    std::map<std::string, Row> by;
    for (const Row& row : result.rows) {
        ASSERT_EQ(row.at("status"), "ok") << row.at("label") << ": " << row.at("error");
        by[row.at("strategy_type") + " " + row.at("camera_tile")] = row;
    }
    for (const char* strategy : {"branching", "multipass"}) {
        SCOPED_TRACE(strategy);
        const Row& plain = by.at(std::string(strategy) + " 0");
        const Row& tiled = by.at(std::string(strategy) + " 8");
        for (const char* same : {"hits", "hit_miss_agreement", "exact_wrong_ppm", "cpu_reference_mismatches", "bytes_vertices",
                                 "voxels_per_ray_mean", "triangles_per_ray_max"})
            EXPECT_EQ(plain.at(same), tiled.at(same)) << same;
        EXPECT_NE(plain.at("cache_ratio_total"), tiled.at("cache_ratio_total"));
    }
    // Multipass in batches of 64 rays: untiled, 12 batches of two image rows; tiled, 12 tiles.
    EXPECT_EQ(by.at("multipass 8").at("multipass_batch_rays"), "64");
    EXPECT_NE(by.at("multipass 0").at("passes_total"), by.at("multipass 8").at("passes_total"));
    // Tiles need whole tiles (else a failed run saying so) and camera rays (else the config is refused).
    const ExperimentResult ragged = runTestConfig(dir, "ragged", config("tile = 5\n", "[strategy]\ntype = \"branching\"\n"));
    ASSERT_EQ(ragged.rows.size(), 1u);
    EXPECT_EQ(ragged.rows[0].at("status"), "failed");
    EXPECT_THAT(ragged.rows[0].at("error"), HasSubstr("camera.tile = 5: the image (32 x 24) is not a whole number of tiles"));
    EXPECT_THAT(errorOf([&] {
                    runTestConfig(dir, "shadowtile", config("tile = 8\n", "[strategy]\ntype = \"branching\"\n[rays]\ntype = \"shadow\"\n"));
                }),
                HasSubstr("camera.tile"));
}

}  // namespace
}  // namespace rtbench
