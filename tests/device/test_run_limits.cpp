// Whole runs at the edges of what the methods handle (issue 7): every input and every scale gets
// a correct result or a failed row with a clear error, and the sweep goes on.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sys/resource.h>
#include <unistd.h>

#include <cmath>
#include <sstream>

#include "strategies/branching/branching_strategy.h"
#include "strategies/multipass/multipass_strategy.h"
#include "strategies/stream_batches.h"
#include "device/gpu_buffers.h"
#include "harness/runner.h"
#include "tests/device/test_device.h"
#include "core/error.h"
#include "tests/harness/test_experiment.h"
#include "tests/temp_dir.h"
#include "tests/error_of.h"
#include "structures/uniform_grid/grid_structure.h"
#include "structures/uniform_grid/uniform_grid.h"
#include "scene/procedural.h"

namespace rtbench {
namespace {
using ::testing::HasSubstr;
using ::testing::Not;

// A tetrahedron scaled and translated, as an OFF file.
std::string tetrahedronOff(double scale, double offset = 0.0) {
    std::ostringstream off;
    off.precision(17);
    off << "OFF\n4 4 0\n";
    for (const char* v : {"0 0 0", "1 0 0", "0 1 0", "0 0 1"}) {
        double x, y, z;
        std::istringstream(v) >> x >> y >> z;
        off << x * scale + offset << " " << y * scale + offset << " " << z * scale + offset << "\n";
    }
    off << "3 0 1 2\n3 0 1 3\n3 0 2 3\n3 1 2 3\n";
    return off.str();
}

class RunLimits : public ::testing::Test {
protected:
    Row runOne(const std::string& scene, const std::string& body) {
        dir_.write("scene.off", scene);
        const ExperimentResult result =
            runTestConfig(dir_, "limits", "[scene]\nsource = \"scene.off\"\n[output]\nimages = false\n" + body);
        EXPECT_EQ(result.rows.size(), 1u);
        return result.rows.at(0);
    }
    TempDir dir_;
};

// The grid covers every group, the fewest rows, and leaves fewer than a row's worth (y - 1) empty.
// Half the physical memory, or half the address-space limit (ulimit -v) when lower: a run under a
// 4 GiB limit is refused with the figure, not ended by a bare std::bad_alloc.
TEST(HostMemoryLimit, HalfThePhysicalMemoryOrHalfTheAddressSpaceLimitWhenLower) {
    constexpr std::uint64_t GiB = std::uint64_t(1) << 30;
    EXPECT_EQ(hostMemoryLimit(24 * GiB, std::uint64_t(RLIM_INFINITY)), 12 * GiB);
    EXPECT_EQ(hostMemoryLimit(24 * GiB, 4 * GiB), 2 * GiB);
    EXPECT_EQ(hostMemoryLimit(2 * GiB, 64 * GiB), 1 * GiB);
    EXPECT_LE(hostMemoryLimit(), hostMemoryLimit(std::uint64_t(sysconf(_SC_PHYS_PAGES)) * std::uint64_t(sysconf(_SC_PAGE_SIZE)),
                                                 std::uint64_t(RLIM_INFINITY)));
}

TEST(WorkgroupGrid, CoversEveryGroupWithTheFewestRowsAndFewerThanOneEmptyGroupPerRow) {
    using Grid = std::pair<std::uint64_t, std::uint64_t>;
    EXPECT_EQ(workgroupGrid(0, 65535), Grid(0, 1));
    EXPECT_EQ(workgroupGrid(1, 65535), Grid(1, 1));
    EXPECT_EQ(workgroupGrid(65535, 65535), Grid(65535, 1));
    EXPECT_EQ(workgroupGrid(65536, 65535), Grid(32768, 2));  // 2048 x 2048 rays of 64: 65,536 groups
    EXPECT_EQ(workgroupGrid(131071, 65535), Grid(43691, 3)); // 131,073 slots, 2 empty
    for (std::uint64_t groups : {1ull, 7ull, 65535ull, 65536ull, 100000ull, 262144ull, 4294967295ull})
        for (std::uint64_t limit : {1ull, 2ull, 1000ull, 65535ull, 2147483647ull}) {
            const auto [x, y] = workgroupGrid(groups, limit);
            EXPECT_LE(x, limit);
            EXPECT_EQ(y, (groups + limit - 1) / limit) << groups << " groups, limit " << limit;
            EXPECT_GE(x * y, groups);
            EXPECT_LT(x * y - groups, y) << groups << " groups, limit " << limit;
        }
}

TEST_F(RunLimits, ASceneScaledBy1e18FailsWithTheRangeInsteadOfAbortingInEmbree) {
    const Row row = runOne(tetrahedronOff(1e18), "[camera]\nwidth = 8\nheight = 8\n");
    EXPECT_EQ(row.at("status"), "failed");
    EXPECT_THAT(row.at("error"), HasSubstr("is out of range: the methods handle vertex coordinates within +-2.749e+11 (2^38)"));
}

TEST_F(RunLimits, ACameraAt1e19FailsWithTheRangeInsteadOfAbortingInEmbree) {
    const Row row = runOne(tetrahedronOff(1.0), "[camera]\nwidth = 8\nheight = 8\nposition = [1e19, 1, 1]\n");
    EXPECT_EQ(row.at("status"), "failed");
    EXPECT_THAT(row.at("error"), HasSubstr("camera: position (1e+19, 1, 1) or look_at"));
    EXPECT_THAT(row.at("error"), HasSubstr("ray origins within +-1.1e+12 (2^40)"));
}

TEST_F(RunLimits, ATetrahedronScaledBy1e40FailsAtOnceInsteadOfHanging) {
    const Row row = runOne(tetrahedronOff(1e-40), "[camera]\nwidth = 8\nheight = 8\n");
    EXPECT_EQ(row.at("status"), "failed");
    EXPECT_THAT(row.at("error"), HasSubstr("too small"));
    EXPECT_THAT(row.at("error"), HasSubstr("at least 1.49e-08 (2^-26)"));
}

TEST_F(RunLimits, ScenesAtTheEdgesOfTheRangeRenderAndAgreeWithEmbree) {
    for (double scale : {1e-7, 1e11}) {
        SCOPED_TRACE(scale);
        const Row row = runOne(tetrahedronOff(scale), "[camera]\nwidth = 16\nheight = 16\n");
        EXPECT_EQ(row.at("status"), "ok") << row.at("error");
        EXPECT_GT(std::stoi(row.at("hits")), 20);
        EXPECT_EQ(row.at("hit_miss_mismatches"), "0");
    }
}

TEST_F(RunLimits, A16384SquaredImageIsRefusedBeforeAnythingIsAllocated) {
    const Row row = runOne(tetrahedronOff(1.0), "[camera]\nwidth = 16384\nheight = 16384\n");
    EXPECT_EQ(row.at("status"), "failed");
    // 268,435,456 rays of 64 bytes (ray and hit record; branching has no buffers of its own),
    // 2^34 bytes: the total is refused (a single binding would not be: the stream would run in batches).
    EXPECT_THAT(row.at("error"), HasSubstr("the run's buffers would take 17179869184 bytes, over "));
    EXPECT_THAT(row.at("error"), HasSubstr("largest device-local heap"));
}

TEST_F(RunLimits, MultipassCountsItsOwnPerRayBuffersInTheRefusal) {
    const Row row = runOne(tetrahedronOff(1.0), "[camera]\nwidth = 16384\nheight = 16384\n[strategy]\ntype = \"multipass\"\n");
    EXPECT_EQ(row.at("status"), "failed");
    // Each ray also has multipass's stencil byte, a traversal state of 16 bytes at least (brute
    // force's), a 16-byte hit state and 16 bytes of counters: 113 bytes x 2^28 rays.
    EXPECT_THAT(row.at("error"), HasSubstr("the run's buffers would take 30333206528 bytes, over "));
}

TEST_F(RunLimits, ASliverTooLongForMinDimFailsNamingTheResolution) {
    // Aspect 2^21: min_dim 2048 asks for 2^32 cells along x.
    const Row row = runOne("OFF\n3 1 0\n0 0 0\n2097152 0 0\n0 1 1\n3 0 1 2\n",
                           "[camera]\nwidth = 8\nheight = 8\n[structure]\nmin_dim = 2048\n");
    EXPECT_EQ(row.at("status"), "failed");
    EXPECT_THAT(row.at("error"), HasSubstr("resolution 4294967296x2048x2048 has more than 2147483647 cells along x"));
}

TEST_F(RunLimits, AFlatSceneGetsOneCellAcrossItsPlane) {
    // 8 triangles in the plane z = 0 at the default min_dim 64: 64 cells along the smaller side.
    const Row row = runOne("OFF\n9 8 0\n0 0 0\n1 0 0\n2 0 0\n0 1 0\n1 1 0\n2 1 0\n0 2 0\n1 2 0\n2 2 0\n"
                           "3 0 1 4\n3 0 4 3\n3 1 2 5\n3 1 5 4\n3 3 4 7\n3 3 7 6\n3 4 5 8\n3 4 8 7\n",
                           "[camera]\nwidth = 16\nheight = 16\nposition = [1, 1, 2]\nlook_at = [1, 1, 0]\n");
    EXPECT_EQ(row.at("status"), "ok") << row.at("error");
    EXPECT_EQ(row.at("grid_res_x") + "x" + row.at("grid_res_y") + "x" + row.at("grid_res_z"), "64x64x1");
    EXPECT_EQ(row.at("hits"), "256");
}

TEST_F(RunLimits, TrianglesDegenerateInFloatAreCountedAndReported) {
    // At x = 1e5 float's spacing is 1/128: the second triangle's vertices 0.001 apart coincide.
    // Said on stderr as the run ends; quiet (-q), only counted (main prints the count).
    dir_.write("scene.off", "OFF\n6 2 0\n0 0 0\n1 0 0\n0 1 0\n100000 0 0\n100000.001 0 0\n100000 0.001 0\n3 0 1 2\n3 3 4 5\n");
    const std::string body = "[scene]\nsource = \"scene.off\"\n[output]\nimages = false\n[camera]\nwidth = 8\nheight = 8\n"
                             "position = [0.2, 0.2, 2]\nlook_at = [0.2, 0.2, 0]\n";
    for (const bool quiet : {false, true}) {
        RunnerOptions options = quietRunnerOptions();
        options.quiet = quiet;
        options.force = true;
        ::testing::internal::CaptureStderr();
        ::testing::internal::CaptureStdout();
        const ExperimentResult result = runTestConfig(dir_, "limits", body, options);
        const std::string err = ::testing::internal::GetCapturedStderr();
        ::testing::internal::GetCapturedStdout();
        ASSERT_EQ(result.rows.size(), 1u);
        const Row& row = result.rows[0];
        EXPECT_EQ(row.at("scene_degenerate"), "1");
        EXPECT_EQ(row.at("warnings"), "1 of 2 triangles are degenerate (zero area in float) and are never hit");
        EXPECT_EQ(result.warned, 1);
        if (quiet)
            EXPECT_THAT(err, Not(HasSubstr("warning"))) << "quiet: counted, not said";
        else
            EXPECT_THAT(err, HasSubstr("warning: 1 of 2 triangles are degenerate (zero area in float) and are never hit"));
    }
}

TEST(HitChecks, ANanDistanceIsNamedAsAnOutOfRangeInputNotNondeterminism) {
    std::vector<gpu::HitRecord> counted(3, gpu::HitRecord{1.0f, 0, 0, 0, 0, 0, 0, 0}), timed = counted;
    timed[1].t = counted[1].t = std::nanf("");
    try {
        expectSameHits(timed, counted, "branching kernel");
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr("branching kernel: ray 1 has a NaN hit distance"));
        EXPECT_THAT(e.what(), Not(HasSubstr("nondeterministic")));
    }
    timed[1].t = counted[1].t = 1.0f;
    timed[0].t = timed[2].t = 2.0f;
    try {
        expectSameHits(timed, counted, "branching kernel");
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_THAT(e.what(), HasSubstr("differ from the instrumented run's on 2 of 3 rays (first: ray 0"));
    }
}

}  // namespace
}  // namespace rtbench

namespace rtbench {
namespace {

using KernelSpecs = VulkanTest;

// A strategy's constants go beside the common ones; one that repeats a common ID is refused by
// name before Vulkan sees it.
TEST_F(KernelSpecs, AStrategyConstantThatRepeatsACommonIdIsRefused) {
    const std::vector<gpu::Ray> rays(8, gpu::Ray{glm::vec4(0.0f), glm::vec4(0, 0, 1, gpu::kNoHitT)});
    const TriangleMesh mesh = christenSceneA();
    GridResolutionRule rule;
    rule.minDim = 4;
    const std::unique_ptr<Structure> structure = gridStructure(buildUniformGrid(mesh, rule));
    GpuBuffers buffers(*vk_, rays, structure->buffers(), structure->params(),
                       multipassBuffers(rays.size(), sizeof(gpu::GridTraversalState), false));
    KernelSpec spec;
    spec.strategyConstants = {{gpu::kSpecQuery, gpu::kQueryAny}};
    EXPECT_THAT(errorOf([&] { buffers.createKernel("uniform_grid_multipass_setup", spec); }),
                HasSubstr("uniform_grid_multipass_setup: specialization constant " + std::to_string(gpu::kSpecQuery) + " given twice"));
    spec.strategyConstants = {{gpu::kSpecTraverseSteps, 3}};
    ComputePipeline pipeline = buffers.createKernel("uniform_grid_multipass_setup", spec);
    vk_->destroy(pipeline);
}

// A stream in batches uploads the structure once, bound by every batch: its bytes count once
// against the heap, however many batches (each batch used to upload its own copy, so 256 batches
// of the bunny's 8.5 MB grid were refused on lavapipe's 2 GiB).
TEST_F(KernelSpecs, BatchesShareOneUploadOfTheStructure) {
    const TriangleMesh mesh = christenSceneA();
    GridResolutionRule rule;
    rule.minDim = 4;
    const std::unique_ptr<Structure> structure = gridStructure(buildUniformGrid(mesh, rule));
    std::uint64_t structureBytes = 0;
    for (const BufferData& b : structure->buffers()) structureBytes += b.bytes;
    const std::uint64_t heap = vk_->info().deviceLocalBytes;
    ASSERT_GT(heap, 2 * structureBytes);
    // Per-ray buffers that leave room for the structure once, not twice.
    const std::vector<BufferSize> perRay = {{"rays", heap - structureBytes - structureBytes / 2}};
    const auto shared = uploadForBatches(*vk_, perRay, structure->buffers());
    ASSERT_TRUE(shared);
    EXPECT_EQ(shared->buffers().size(), structure->buffers().size());
    const std::vector<BufferSize> tooMany = {{"rays", heap - structureBytes + 1}};
    EXPECT_THAT(errorOf([&] { uploadForBatches(*vk_, tooMany, structure->buffers()); }),
                HasSubstr("largest device-local heap"));
    // Two batches bound to it trace what one stream does.
    std::vector<gpu::Ray> rays;
    for (int i = 0; i < 128; ++i)
        rays.push_back(gpu::Ray{glm::vec4(-4.0f + 0.06f * float(i), 0.5f, -10.0f, 0.0f), glm::vec4(0, 0, 1, gpu::kNoHitT)});
    auto trace = [&](const std::vector<gpu::Ray>& part, GpuBuffers& buffers) {
        const KernelSpec spec = structureKernelSpec(*structure, 64, gpu::kQueryClosest, {});
        ComputePipeline pipeline = buffers.createKernel(structure->kernelPrefix() + "_branching", spec);
        vk_->dispatch(pipeline, buffers.descriptorSet(pipeline), buffers.pushConstants(), part.size(), buffers.passCounters());
        vk_->destroy(pipeline);
        return buffers.downloadHits();
    };
    GpuBuffers whole(*vk_, rays, structure->buffers(), structure->params());
    const std::vector<gpu::HitRecord> expected = trace(rays, whole);
    const std::vector<gpu::Ray> first(rays.begin(), rays.begin() + 64), second(rays.begin() + 64, rays.end());
    GpuBuffers a(*vk_, first, shared, structure->params()), b(*vk_, second, shared, structure->params());
    std::vector<gpu::HitRecord> hits = trace(first, a);
    const std::vector<gpu::HitRecord> rest = trace(second, b);
    hits.insert(hits.end(), rest.begin(), rest.end());
    ASSERT_EQ(hits.size(), expected.size());
    int hitCount = 0;
    for (std::size_t i = 0; i < hits.size(); ++i) {
        EXPECT_EQ(hits[i].t, expected[i].t) << i;
        EXPECT_EQ(hits[i].primitive, expected[i].primitive) << i;
        hitCount += expected[i].t < gpu::kNoHitT;
    }
    EXPECT_GT(hitCount, 10);
}

}  // namespace
}  // namespace rtbench
