// Purcell 2002 Fig. 9's texture cache (methods/cache): the simulator on hand-made traces whose
// hits are counted in the comments; the replay of whole runs against counts derived by hand and
// against the bandwidth accounting, a second formulation (counters x unit costs) of the bytes
// the traced reads of the kernels' own source add up to; and a run through the runner.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "methods/cache/cache_replay.h"
#include "methods/cache/memory_trace.h"
#include "strategies/multipass/multipass_simulator.h"
#include "core/error.h"
#include "scene/procedural.h"
#include "tests/error_of.h"
#include "tests/harness/test_experiment.h"
#include "tests/methods/hand_scenes.h"
#include "tests/methods/test_rays.h"

namespace rtbench {
namespace {
using ::testing::HasSubstr;

CacheConfig cacheOf(std::uint64_t size, std::uint64_t line, std::uint64_t ways) {
    CacheConfig c;
    c.sizeBytes = size;
    c.lineBytes = line;
    c.ways = ways;
    return c;
}

constexpr MemoryKind kCells = MemoryKind::Cells;

// A device any of these scenes fits in (the structures refuse buffers over its binding range).
DeviceInfo roomyDevice() {
    DeviceInfo device;
    device.maxStorageBufferRange = 1u << 27;
    return device;
}

TEST(CacheSimulator, DirectMappedLinesConflictInTheirSet) {
    CacheSimulator cache(cacheOf(32, 16, 1));  // 2 sets of one 16-byte line
    cache.read(kCells, 0, 4);   // line 0, set 0: miss
    cache.read(kCells, 32, 4);  // line 2, set 0: miss, line 0 out
    cache.read(kCells, 0, 4);   // line 0: miss again
    cache.read(kCells, 16, 4);  // line 1, set 1: miss
    cache.read(kCells, 20, 4);  // line 1: hit
    EXPECT_EQ(cache.stats(kCells).lineLookups, 5u);
    EXPECT_EQ(cache.stats(kCells).lineHits, 1u);
    EXPECT_EQ(cache.stats(kCells).readBytes, 20u);
    EXPECT_EQ(cache.bytesWith(kCells), 4u * 16u);  // four lines fetched
}

TEST(CacheSimulator, AReadTouchesEveryLineItSpans) {
    CacheSimulator cache(cacheOf(1024, 16, 1));
    cache.read(kCells, 0, 4);    // line 0: miss
    cache.read(kCells, 4, 4);    // the same line: hit
    cache.read(kCells, 12, 8);   // lines 0 (hit) and 1 (miss)
    cache.read(kCells, 16, 16);  // line 1: hit
    EXPECT_EQ(cache.stats(kCells).lineLookups, 5u);
    EXPECT_EQ(cache.stats(kCells).lineHits, 3u);
}

// Lines 0, 1, 0, 2, 1 through one 2-way set (least recently used out) and through two direct-mapped
// sets of the same size.
TEST(CacheSimulator, AssociativityChangesWhatStays) {
    const std::uint64_t lines[] = {0, 1, 0, 2, 1};
    CacheSimulator twoWay(cacheOf(32, 16, 2));  // one set: 0 miss, 1 miss, 0 hit, 2 miss (1 out), 1 miss
    CacheSimulator direct(cacheOf(32, 16, 1));  // sets {0, 2} and {1}: 0 miss, 1 miss, 0 hit, 2 miss, 1 hit
    for (const std::uint64_t line : lines) {
        twoWay.read(kCells, line * 16, 1);
        direct.read(kCells, line * 16, 1);
    }
    EXPECT_EQ(twoWay.sets(), 1u);
    EXPECT_EQ(twoWay.stats(kCells).lineHits, 1u);
    EXPECT_EQ(direct.stats(kCells).lineHits, 2u);
}

// Purcell's cache: 64 KB of 48-byte lines is 1,365 sets, not a power of two: lines 1,365 apart
// conflict, lines 1,024 apart (a mask's conflict) do not.
TEST(CacheSimulator, PurcellsCacheHas1365SetsByTheModulo) {
    CacheSimulator cache{CacheConfig{}};
    EXPECT_EQ(cache.sets(), 1365u);
    EXPECT_EQ(cache.capacityBytes(), 65520u);
    cache.read(kCells, 0, 1);
    cache.read(kCells, 1024 * 48, 1);
    cache.read(kCells, 0, 1);  // hit: line 1,024 sits in set 1,024
    cache.read(kCells, 1365 * 48, 1);
    cache.read(kCells, 0, 1);  // miss: line 1,365 took set 0
    EXPECT_EQ(cache.stats(kCells).lineHits, 1u);
}

TEST(CacheSimulator, WritesCostTheirBytesAndCacheNothing) {
    CacheSimulator cache(cacheOf(1024, 16, 1));
    cache.write(MemoryKind::Stencil, 0, 1);
    cache.read(MemoryKind::Stencil, 0, 1);  // a miss: the write brought nothing in
    EXPECT_EQ(cache.stats(MemoryKind::Stencil).lineHits, 0u);
    EXPECT_EQ(cache.stats(MemoryKind::Stencil).bytesWithout(), 2u);
    EXPECT_EQ(cache.bytesWith(MemoryKind::Stencil), 16u + 1u);
}

// A pass's writes make the lines they touch stale at its end; within the pass they stay (a pass
// renders to another texture than it reads), and lines not written stay after it.
TEST(CacheSimulator, APassEndDropsTheLinesItWrote) {
    CacheSimulator cache(cacheOf(64, 16, 2));  // 2 sets of two 16-byte lines
    cache.read(kCells, 0, 4);                   // line 0, set 0: miss
    cache.read(kCells, 32, 4);                  // line 2, set 0: miss
    cache.read(kCells, 16, 4);                  // line 1, set 1: miss
    cache.write(MemoryKind::State, 0, 20);      // lines 0 and 1
    cache.read(kCells, 0, 4);                   // line 0: hit, the pass has not ended
    cache.endPass();
    cache.read(kCells, 0, 4);                   // line 0: miss, dropped; it takes the emptied way
    cache.read(kCells, 32, 4);                  // line 2: hit, never written and not pushed out
    cache.read(kCells, 16, 4);                  // line 1: miss, dropped
    EXPECT_EQ(cache.stats(kCells).lineLookups, 7u);
    EXPECT_EQ(cache.stats(kCells).lineHits, 2u);
    cache.endPass();                            // nothing written since: nothing dropped
    cache.read(kCells, 0, 4);
    EXPECT_EQ(cache.stats(kCells).lineHits, 3u);
}

TEST(CacheSimulator, RefusesACacheWithoutAWholeSet) {
    EXPECT_THAT(errorOf([] { CacheSimulator(cacheOf(40, 48, 1)); }), HasSubstr("40 bytes hold no set of 1 lines of 48 bytes"));
    EXPECT_THROW(CacheSimulator(cacheOf(64, 0, 1)), Error);
    EXPECT_THROW(CacheSimulator(cacheOf(64, 16, 0)), Error);
}

TEST(MemoryTrace, PlacesBuffersAtBoundariesAndRefusesOthers) {
    CacheSimulator cache(cacheOf(1 << 20, 1, 1));  // 1-byte lines: a lookup's line is its address
    MemoryTrace trace(cache);
    std::vector<std::uint8_t> a(300), b(10), other(4);
    trace.place(a.data(), a.size());
    trace.place(b.data(), b.size());
    trace.read(kCells, &b[3], 1);  // device address 512 + 3
    trace.read(kCells, &a[3], 1);  // 3
    trace.read(kCells, &b[3], 1);  // 515 again: a hit
    EXPECT_EQ(cache.stats(kCells).lineHits, 1u);
    EXPECT_THAT(errorOf([&] { trace.read(kCells, other.data(), 1); }), HasSubstr("outside every buffer placed"));
    EXPECT_THAT(errorOf([&] { trace.read(kCells, &b[8], 4); }), HasSubstr("outside every buffer placed"));
}

TEST(MemoryTrace, TracedArraysReportOnlyWithinAScope) {
    CacheSimulator cache(cacheOf(1024, 16, 1));
    MemoryTrace trace(cache);
    const std::vector<std::uint32_t> values = {7, 8, 9};
    TracedArray<std::uint32_t, MemoryKind::TriangleList> array;
    array = values.data();
    EXPECT_EQ(array[1], 8u);  // no scope: no trace, nothing placed needed
    trace.place(values.data(), 12);
    {
        const MemoryTrace::Scope scope(trace);
        EXPECT_EQ(array[2], 9u);
    }
    EXPECT_EQ(array[0], 7u);
    EXPECT_EQ(cache.stats(MemoryKind::TriangleList).readBytes, 4u);
}

// ---- whole runs, counted by hand ----

// Two triangles far from three rays (each ray misses both and tests both). Placed at multiples of
// 768 bytes (of 256 and of the 48-byte line): the vertices (96 bytes) at 0, the rays at 768, the
// hit records at 1536. Triangle 0 is line 0, triangle 1 line 1; ray 0 (768-799) line 16, ray 1
// (800-831) lines 16 and 17, ray 2 (832-863) line 17.
TEST(CacheReplay, BranchingOverTwoTrianglesCountedByHand) {
    const TriangleMesh mesh = hand::meshOf({{glm::vec3(0, 0, 10), glm::vec3(1, 0, 10), glm::vec3(0, 1, 10)},
                                            {glm::vec3(0, 0, 20), glm::vec3(1, 0, 20), glm::vec3(0, 1, 20)}});
    const auto brute = hand::bruteOf(mesh, roomyDevice());
    const std::vector<gpu::Ray> rays(3, hand::ray({5, 5, 0}, {0, 0, 1}));
    const CacheSimulator cache = branchingCacheReplay(*brute, rays, gpu::kQueryClosest, CacheConfig{});
    const CacheKindStats& state = cache.stats(MemoryKind::State);
    const CacheKindStats& vertices = cache.stats(MemoryKind::Vertices);
    EXPECT_EQ(state.lineLookups, 4u);  // lines 16; 16, 17; 17
    EXPECT_EQ(state.lineHits, 2u);     // ray 1's line 16, ray 2's line 17
    EXPECT_EQ(vertices.lineLookups, 6u);
    EXPECT_EQ(vertices.lineHits, 4u);  // both triangles miss once, for ray 0
    EXPECT_EQ(vertices.readBytes, 6u * 48u);
    EXPECT_EQ(cache.stats(MemoryKind::Output).writeBytes, 3u * 16u);
    EXPECT_EQ(cache.bytesWith(MemoryKind::Output), 3u * 16u);
}

// One ray, one triangle it hits, multipass (M = 1): setup, one intersect pass, write. Placed 768
// bytes apart: the vertices (48 bytes, line 0), the ray (line 16), the stencil (line 32), the
// traversal state (16 bytes, line 48), the hit state (line 64), the records.
TEST(CacheReplay, MultipassOverOneTriangleCountedByHand) {
    const TriangleMesh mesh = hand::meshOf({{glm::vec3(0, 0, 10), glm::vec3(10, 0, 10), glm::vec3(0, 10, 10)}});
    const auto brute = hand::bruteOf(mesh, roomyDevice());
    const std::vector<gpu::Ray> rays = {hand::ray({1, 1, 0}, {0, 0, 1})};
    const MultipassOptions options;
    const CacheSimulator cache = multipassCacheReplay(*brute, rays, options, gpu::kQueryClosest, 0, CacheConfig{});
    EXPECT_EQ(simulateMultipass(*brute, rays, options).counts.sequence,
              (std::vector<PassKind>{PassKind::Setup, PassKind::Intersect, PassKind::Write}));
    // State reads: setup's ray (miss); the intersect pass's ray (hit), traversal state (miss) and
    // hit state (miss); the write pass's hit state (miss: the intersect pass wrote it, so its line
    // left the cache at the pass's end).
    EXPECT_EQ(cache.stats(MemoryKind::State).lineLookups, 5u);
    EXPECT_EQ(cache.stats(MemoryKind::State).lineHits, 1u);
    // Writes: setup's and the intersect pass's traversal and hit state, 16 bytes each.
    EXPECT_EQ(cache.stats(MemoryKind::State).writeBytes, 64u);
    // The stencil: read once by the intersect pass (a miss); written by setup and by the intersect pass.
    EXPECT_EQ(cache.stats(MemoryKind::Stencil).lineLookups, 1u);
    EXPECT_EQ(cache.bytesWith(MemoryKind::Stencil), 48u + 2u);
    EXPECT_EQ(cache.stats(MemoryKind::Vertices).lineLookups, 1u);
    EXPECT_EQ(cache.stats(MemoryKind::Vertices).lineHits, 0u);
}

// ---- the replay against the accounting ----

// Every structure, branching and multipass (Purcell's K = M = 1, his unrolling with and without
// suppressed reads, batches): the replay's bytes without the cache, by data type, are the
// accounting's, which multiplies counters by unit costs; and tracing changes no hit.
TEST(CacheReplay, BytesWithoutTheCacheAreTheAccountings) {
    const TriangleMesh mesh = christenSceneB();
    const std::vector<gpu::Ray> rays = randomRays(mesh.bounds(), 700, 5);
    for (const hand::StructureCase& c : {hand::bruteCase(), hand::gridCase({9, 7, 8}), hand::bvhCase(4)}) {
        SCOPED_TRACE(c.name);
        const auto structure = c.build(mesh, roomyDevice());
        const CacheConfig config = cacheOf(4096, 32, 2);
        Row row;
        const ArchitectureMetrics branching = branchingMetrics(structure->trace(rays), 0, 0, structure->costs());
        EXPECT_EQ(writeCacheColumns(branchingCacheReplay(*structure, rays, gpu::kQueryClosest, config), branching.bytes, row), "");
        for (const auto& [k, m, suppress, batch] : std::vector<std::tuple<unsigned, unsigned, bool, std::uint64_t>>{
                 {1, 1, false, 0}, {4, 2, false, 0}, {4, 2, true, 0}, {1, 1, false, 256}}) {
            SCOPED_TRACE("K " + std::to_string(k) + ", M " + std::to_string(m) + (suppress ? ", suppressed" : "") +
                         ", batch " + std::to_string(batch));
            MultipassOptions options;
            options.traverseStepsPerPass = k;
            options.intersectionsPerPass = m;
            options.suppressFinishedReads = suppress;
            const MultipassResult plain = simulateMultipass(*structure, rays, options, gpu::kQueryClosest, batch);
            CacheSimulator cache(config);
            MemoryTrace trace(cache);
            for (const StructureBuffer& b : structure->buffers()) trace.place(b.data, b.bytes);
            const MultipassResult traced = simulateMultipass(*structure, rays, options, gpu::kQueryClosest, batch, &trace);
            EXPECT_TRUE(traced.counts == plain.counts);
            expectIdentical(traced.hits, plain.hits);
            const ArchitectureMetrics accounted = multipassMetrics(plain.hits, plain.counts, options, structure->costs());
            EXPECT_EQ(writeCacheColumns(cache, accounted.bytes, row), "");
            EXPECT_GT(cache.stats(MemoryKind::Stencil).lineHits, 0u);
        }
    }
}

TEST(CacheReplay, ADifferenceFromTheAccountingNamesTheDataType) {
    CacheSimulator cache(cacheOf(1024, 16, 1));
    cache.read(MemoryKind::Vertices, 0, 48);
    Bandwidth accounted;
    accounted.vertices = 96;
    Row row;
    EXPECT_THAT(writeCacheColumns(cache, accounted, row), HasSubstr("vertices 48 bytes in the cache replay, 96 accounted"));
    EXPECT_EQ(row.at("cache_ratio_vertices"), "1");
    EXPECT_EQ(row.at("cache_hit_rate_vertices"), "0");
    EXPECT_EQ(row.count("cache_hit_rate_cells"), 0u);
}

TEST(CacheReplay, RefusesTheDeviceControlledMultipass) {
    const TriangleMesh mesh = christenSceneB();
    const auto brute = hand::bruteOf(mesh, roomyDevice());
    MultipassOptions options;
    options.deviceControl = true;
    EXPECT_THAT(errorOf([&] { multipassCacheReplay(*brute, {}, options, gpu::kQueryClosest, 0, CacheConfig{}); }),
                HasSubstr("strategy.control = host"));
}

// Through the runner: branching and multipass rows carry the cache columns and stay ok; the keys
// are refused where no run reads them.
TEST(CacheReplay, RunsWriteTheCacheColumns) {
    TempDir dir;
    const ExperimentResult result =
        runTestConfig(dir, "cache",
                      "[scene]\nsource = \"procedural:christen_b\"\n[camera]\nwidth = 32\nheight = 24\n"
                      "[structure]\ntype = [\"uniform_grid\", \"bvh\"]\nmin_dim = 8\n"
                      "[strategy]\ntype = [\"branching\", \"multipass\"]\n[cache]\nsimulate = true\nline_bytes = 64\n");
    ASSERT_EQ(result.rows.size(), 4u);
    for (const Row& row : result.rows) {
        SCOPED_TRACE(cellText(row, "label"));
        EXPECT_EQ(cellText(row, "status"), "ok") << cellText(row, "error");
        EXPECT_EQ(cellText(row, "cache_capacity_bytes"), "65536");
        EXPECT_NE(cellText(row, "cache_ratio_total"), "");
        EXPECT_NE(cellText(row, "cache_hit_rate_vertices"), "");
        EXPECT_EQ(cellText(row, "cache_hit_rate_stencil").empty(), cellText(row, "strategy_type") == "branching");
    }
    EXPECT_THAT(errorOf([&] {
                    runTestConfig(dir, "plaincache",
                                  "[scene]\nsource = \"procedural:christen_b\"\n[strategy]\ntype = \"plain\"\n[cache]\nsimulate = true\n");
                }),
                HasSubstr("cache.simulate"));
}

}  // namespace
}  // namespace rtbench
