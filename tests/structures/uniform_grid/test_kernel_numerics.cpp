// The kernels' arithmetic on lavapipe against the same source compiled as C++, on the inputs
// most likely to expose a difference between the two machines (issue 7): long thin triangles
// (slivers, nearly degenerate in float) and scenes at both ends of the range of
// scene/scene_limits.h, with both ray-triangle tests. Hit records, per-ray counters and the
// saved DDA state must be identical bit for bit.
#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <random>

#include "strategies/branching/branching_strategy.h"
#include "strategies/multipass/multipass_strategy.h"
#include "device/gpu_buffers.h"
#include "methods/metrics.h"
#include "scene/camera.h"
#include "structures/uniform_grid/grid_reference.h"
#include "structures/uniform_grid/grid_structure.h"
#include "structures/uniform_grid/uniform_grid.h"
#include "scene/procedural.h"
#include "tests/device/test_device.h"

namespace rtbench {
namespace {

// `count` slivers of the given length and width in [0, 1]^3 (fixed seed), then scaled: random
// orientation, or (axisAligned) along the axes, in planes of constant coordinate.
TriangleMesh slivers(unsigned count, float length, float width, float scale, bool axisAligned) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::normal_distribution<float> g;
    TriangleMesh mesh;
    mesh.name = "slivers";
    for (unsigned i = 0; i < count; ++i) {
        const glm::vec3 centre(u(rng), u(rng), u(rng));
        glm::vec3 along = glm::normalize(glm::vec3(g(rng), g(rng), g(rng)));
        glm::vec3 across = glm::normalize(glm::cross(along, glm::vec3(g(rng), g(rng), g(rng))));
        if (axisAligned) along = glm::vec3(0.0f), along[i % 3] = 1.0f, across = glm::vec3(0.0f), across[(i + 1) % 3] = 1.0f;
        const unsigned base = unsigned(mesh.vertices.size());
        for (glm::vec3 v : {centre - 0.5f * length * along, centre + 0.5f * length * along, centre + width * across})
            mesh.vertices.push_back(v * scale);
        mesh.triangles.emplace_back(base, base + 1, base + 2);
    }
    return mesh;
}

std::uint64_t differingRecords(const std::vector<gpu::HitRecord>& a, const std::vector<gpu::HitRecord>& b) {
    std::uint64_t differing = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (std::memcmp(&a[i], &b[i], sizeof(gpu::HitRecord)) && ++differing <= 3)
            ADD_FAILURE() << "ray " << i << ": GPU t=" << a[i].t << " prim=" << a[i].primitive << " voxels="
                          << a[i].cellsVisited << " | CPU t=" << b[i].t << " prim=" << b[i].primitive
                          << " voxels=" << b[i].cellsVisited;
    return differing;
}

using KernelNumerics = VulkanTest;

TEST_F(KernelNumerics, SliversAtTheEdgesOfTheRangeMatchTheCpuReferenceBitForBit) {
    for (bool axisAligned : {false, true})
        for (float width : {1e-3f, 2e-8f})  // 2e-8: the third vertex within a few ulps of the edge
            for (float scale : {1e-7f, 1.0f, 1e11f}) {
                SCOPED_TRACE("axis-aligned " + std::to_string(axisAligned) + " width " + std::to_string(width) +
                             " scale " + std::to_string(scale));
                const TriangleMesh mesh = slivers(20000, 0.05f, width, scale, axisAligned);
                GridResolutionRule rule;
                rule.minDim = 16;
                const UniformGrid grid = buildUniformGrid(mesh, rule);
                const std::vector<gpu::Ray> rays = generatePrimaryRays(fitCamera(mesh.bounds()), 96, 96);
                for (std::uint32_t test : {gpu::kTriangleTestMollerTrumbore, gpu::kTriangleTestWatertight}) {
                    SCOPED_TRACE("triangle test " + std::to_string(test));
                    const std::unique_ptr<Structure> structure = gridStructure(grid);
                    structure->setTriangleTest(test);
                    const BranchingRun run = runBranching(*vk_, *structure, rays, {64, 0, 1});
                    EXPECT_EQ(differingRecords(run.hits, structure->trace(rays)), 0u);
                    if (test == gpu::kTriangleTestMollerTrumbore) {
                        EXPECT_EQ(differingRecords(run.hits, traceGridReference(grid, rays)), 0u);
                    }
                    if (width > 1e-4f) {  // wide enough to be seen
                        EXPECT_GT(workStats(run.hits).hits, 500u);
                    }
                }
            }
}

// Hit records do not show the DDA's state; multipass saves it between passes, so the GPU's
// boundary distances (tMax per axis), exit distance and voxel can be compared after the setup
// pass and after a traverse pass of 8 steps.
TEST_F(KernelNumerics, SavedDdaStateEqualsTheCpusAfterSetupAndTraversal) {
    const TriangleMesh mesh = christenSceneB();
    for (unsigned minDim : {3u, 64u}) {
        SCOPED_TRACE("min_dim " + std::to_string(minDim));
        GridResolutionRule rule;
        rule.minDim = minDim;
        const UniformGrid grid = buildUniformGrid(mesh, rule);
        std::mt19937 rng(minDim);
        std::uniform_real_distribution<float> u(0.0f, 1.0f), s(-1.0f, 1.0f);
        const Bounds3 box = mesh.bounds();
        std::vector<gpu::Ray> rays;
        for (int i = 0; i < 50000; ++i) {
            const glm::vec3 o = box.min - 0.3f * box.extent() + glm::vec3(u(rng), u(rng), u(rng)) * 1.6f * box.extent();
            rays.push_back({glm::vec4(o, 0.0f), glm::vec4(s(rng), s(rng), s(rng), gpu::kNoHitT)});
        }
        const std::unique_ptr<Structure> structure = gridStructure(grid);
        GpuBuffers buffers(*vk_, rays, structure->buffers(), structure->params(),
                           multipassBuffers(rays.size(), sizeof(gpu::GridTraversalState), false));
        KernelSpec spec;
        spec.strategyConstants = {{gpu::kSpecTraverseSteps, 8}};
        for (const char* kernel : {"uniform_grid_multipass_setup", "uniform_grid_multipass_traverse"}) {
            ComputePipeline pipeline = buffers.createKernel(kernel, spec);
            vk_->dispatch(pipeline, buffers.descriptorSet(pipeline), buffers.pushConstants(), rays.size());
            vk_->destroy(pipeline);
        }
        const std::vector<std::uint8_t> gpuStates = downloadTraversalStates(buffers);
        gridref::GridKernels steps = gridKernels(grid);
        steps.traverseStepsPerPass = 8;
        std::uint64_t differing = 0;
        for (std::size_t i = 0; i < rays.size(); ++i) {
            gpu::GridTraversalState state;
            gpu::RayHitState hit;
            gridref::GridKernels::MpEvents events = steps.mpNoEvents();
            if (steps.mpSetup(rays[i], state, hit, events) == gpu::kStateTraversing)
                steps.mpTraverse(rays[i], state, hit, events);
            differing += std::memcmp(&state, &gpuStates[i * sizeof state], sizeof state) != 0;
        }
        EXPECT_EQ(differing, 0u);
    }
}

}  // namespace
}  // namespace rtbench
