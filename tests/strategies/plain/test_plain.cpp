// The plain twin of the branching kernel (methods/plain): the same kernel dividing as the device
// does. What can disagree with it: hand-made records (hitMismatches), the SPIR-V (the kernel must
// read the specialization constant the strategy sets), and whole runs judged against the exact
// reference and beside the branching kernel's on the same rays.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

#include "device/embedded_kernels.h"
#include "harness/runner.h"
#include "strategies/plain/plain_strategy.h"
#include "tests/device/test_device.h"
#include "tests/harness/test_experiment.h"
#include "tests/temp_dir.h"

namespace rtbench {
namespace {

TEST(Plain, HitMismatchesComparesTheHitNotTheWork) {
    gpu::HitRecord a{};
    a.t = 1.0f;
    a.primitive = 3;
    a.u = 0.25f;
    a.v = 0.5f;
    std::vector<gpu::HitRecord> left(5, a), right(5, a);
    right[0].cellsVisited = 7;                          // work only: the same hit
    right[1].t = std::nextafter(1.0f, 2.0f);            // one ulp further
    right[2].u = 0.3f;
    right[3].v = 0.6f;
    right[4].primitive = 4;
    EXPECT_EQ(hitMismatches(left, right), 4u);
    EXPECT_EQ(hitMismatches(left, left), 0u);
    EXPECT_THROW(hitMismatches(left, std::vector<gpu::HitRecord>(4, a)), Error);
}

// The strategy's one difference from branching is kSpecNativeDivision: every structure's branching
// kernel must declare it (OpDecorate %id SpecId 20) and read it (an instruction other than its
// name, decoration and definition takes %id), or setting it would change nothing.
TEST(Plain, EveryBranchingKernelReadsTheNativeDivisionConstant) {
    const std::uint32_t kOpName = 5, kOpSpecConstant = 50, kOpDecorate = 71, kDecorationSpecId = 1;
    for (const char* kernel : {"uniform_grid_branching", "bvh_branching", "brute_force_branching"}) {
        SCOPED_TRACE(kernel);
        const std::span<const std::uint32_t> words = embeddedKernel(kernel);
        // Instructions start after the 5-word header; each starts with (word count << 16) | opcode.
        std::vector<std::pair<std::size_t, std::uint32_t>> instructions;  // (first word, opcode)
        for (std::size_t i = 5; i < words.size(); i += std::max<std::uint32_t>(words[i] >> 16, 1u))
            instructions.emplace_back(i, words[i] & 0xFFFFu);
        std::uint32_t id = 0;
        for (const auto& [i, opcode] : instructions)
            if (opcode == kOpDecorate && words[i + 2] == kDecorationSpecId && words[i + 3] == gpu::kSpecNativeDivision)
                id = words[i + 1];
        ASSERT_NE(id, 0u) << "no specialization constant with SpecId " << gpu::kSpecNativeDivision;
        int uses = 0;
        for (const auto& [i, opcode] : instructions) {
            if (opcode == kOpName || opcode == kOpDecorate || opcode == kOpSpecConstant) continue;
            for (std::size_t w = i + 1; w < i + (words[i] >> 16); ++w) uses += words[w] == id;
        }
        EXPECT_GT(uses, 0) << "the kernel declares the constant but never reads it";
    }
}

ExperimentResult runConfig(TempDir& dir, const std::string& body) { return runTestConfig(dir, "plain", body); }

// Scene B through each structure, closest and any hit: plain's rows are ok against the exact
// reference, with no work counted, and where the device's division is IEEE's (llvmpipe's is
// LLVM's fdiv) its hits are the CPU reference's, bit for bit, and so the branching kernel's.
TEST(Plain, RunsBesideBranchingOnTheSameRays) {
    TempDir dir;
    const ExperimentResult result = runConfig(
        dir, "[scene]\nsource = \"procedural:christen_b\"\n[camera]\nwidth = 40\nheight = 30\n"
             "[structure]\ntype = [\"uniform_grid\", \"bvh\", \"brute_force\"]\nmin_dim = 8\n"
             "[strategy]\ntype = [\"branching\", \"plain\"]\n[rays]\ntype = [\"primary\", \"shadow\"]\n");
    ASSERT_EQ(result.rows.size(), 12u);
    const bool llvmpipe = VulkanContext(testDeviceName(), false).info().name.find("llvmpipe") != std::string::npos;
    int plain = 0;
    for (const Row& row : result.rows) {
        SCOPED_TRACE(row.at("label"));
        EXPECT_EQ(row.at("status"), "ok") << row.at("error");
        if (row.at("label").find("plain") == std::string::npos) continue;
        ++plain;
        EXPECT_EQ(cellText(row, "cpu_reference_mismatches"), "");
        EXPECT_EQ(cellText(row, "work_per_ray_mean"), "");
        EXPECT_EQ(cellText(row, "stream_batches"), "1");
        if (llvmpipe) {
            EXPECT_EQ(cellText(row, "plain_cpu_differing"), "0");
        }
    }
    EXPECT_EQ(plain, 6);
}

}  // namespace
}  // namespace rtbench
