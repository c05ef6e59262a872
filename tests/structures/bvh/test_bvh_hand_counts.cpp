// The BVH counted by hand (issue 15 §6.3-6.4): the flattened tree's statistics (nodes, leaves,
// depth, SAH cost, bytes), the order the walk takes children in (nearer first), the nodes, leaves
// and triangles a ray visits, the bytes read, and the multipass accounting with its node stack, on
// scenes small enough that every number is derived in a comment. The kernels and the CPU
// reference share bvh_traversal.glsl, so they are checked against these numbers, not each other.
#include <gtest/gtest.h>

#include "methods/accounting.h"
#include "tests/device/test_device.h"
#include "tests/methods/hand_scenes.h"

namespace rtbench {
namespace {
using namespace hand;
using gpu::kNoHit;

// Surface area of a box: 2 (xy + yz + zx), as structures/bvh/bvh_build.cpp computes it.
//   valley box [-2,2] x [0,4] x [0,2]: 2 (16 + 8 + 8) = 64
//   each valley triangle's box, [0,2] or [-2,0] x [0,4] x [0,2]: 2 (8 + 8 + 4) = 40

TEST(BvhHandCounts, TheValleyWithLeafSize1IsARootAndTwoLeaves) {
    const FlatBvh bvh = bvhOf(valley(), 1);
    ASSERT_EQ(bvh.nodes.size(), 1u);
    EXPECT_EQ(bvh.stats.innerNodes, 1u);
    EXPECT_EQ(bvh.stats.leaves, 2u);
    EXPECT_EQ(bvh.stats.references, 2u);
    EXPECT_EQ(bvh.stats.largestLeaf, 1u);
    EXPECT_EQ(bvh.stats.depth, 1u);  // edges from the root to the deepest leaf
    // SAH (traversal and intersection cost 1): the root 1 x 64/64, each leaf 1 triangle x 40/64.
    EXPECT_DOUBLE_EQ(bvh.stats.sahCost, 1.0 + 40.0 / 64 + 40.0 / 64);  // 2.25
    // One 80-byte node, 2 list entries of 4 bytes, 2 triangles of 48 bytes: 80 + 8 + 96.
    EXPECT_EQ(bvh.stats.bytes, 184u);
    EXPECT_EQ(glm::vec3(bvh.params.boundsMin), glm::vec3(-2, 0, 0));
    EXPECT_EQ(glm::vec3(bvh.params.boundsMax), glm::vec3(2, 4, 2));
    // Both children are leaves of one triangle whose box is that triangle's.
    const gpu::BvhNode& root = bvh.nodes[0];
    for (int c = 0; c < 2; ++c) {
        const std::uint32_t ref = c ? root.children.y : root.children.x;
        ASSERT_TRUE(ref & gpu::kBvhLeaf);
        EXPECT_EQ((ref >> 24) & 0x7Fu, 0u);  // count - 1
        const std::uint32_t tri = bvh.triangleList.at(ref & 0x00FFFFFFu);
        const glm::vec3 lo(c ? root.min1 : root.min0), hi(c ? root.max1 : root.max0);
        EXPECT_EQ(lo, tri == 0 ? glm::vec3(0, 0, 0) : glm::vec3(-2, 0, 0)) << "child " << c;
        EXPECT_EQ(hi, tri == 0 ? glm::vec3(2, 4, 2) : glm::vec3(0, 4, 2)) << "child " << c;
    }
}

TEST(BvhHandCounts, TheValleyWithLeafSize2IsARootWithOneLeaf) {
    const FlatBvh bvh = bvhOf(valley(), 2);
    ASSERT_EQ(bvh.nodes.size(), 1u);
    EXPECT_EQ(bvh.nodes[0].children.y, gpu::kBvhNone);
    EXPECT_EQ(bvh.stats.leaves, 1u);
    EXPECT_EQ(bvh.stats.depth, 1u);
    EXPECT_EQ(bvh.stats.largestLeaf, 2u);
    EXPECT_EQ(bvh.triangleList, (std::vector<std::uint32_t>{0, 1}));  // ids ascending in a leaf
    // The root 1 (a traversal), its leaf 2 triangles x 64/64.
    EXPECT_DOUBLE_EQ(bvh.stats.sahCost, 1.0 + 2.0);
    EXPECT_EQ(bvh.stats.bytes, 80u + 8u + 96u);
}

// Two unit squares, each split along its diagonal y = x: triangles 0, 1 at z = 0 (far from a ray
// coming down from z = 5), 2, 3 at z = 1 (near). Triangles 0 and 2 are the lower-right halves.
TriangleMesh twoFloors() {
    std::vector<Tri> tris;
    for (float z : {0.0f, 1.0f}) {
        tris.push_back({glm::vec3(0, 0, z), glm::vec3(1, 0, z), glm::vec3(1, 1, z)});
        tris.push_back({glm::vec3(0, 0, z), glm::vec3(1, 1, z), glm::vec3(0, 1, z)});
    }
    return meshOf(tris);
}

// With leaf size 1, SAH puts each floor under its own node: boxes flat at z = 0 and z = 1 (area
// 2 each) beat any split mixing the floors (boxes [0,1]^3, area 6 each).
//   nodes 3, leaves 4, depth 2; SAH: root 6/6 + two floor nodes 2/6 each + four leaves 1 x 2/6
//   each = 1 + 4/6 + 8/6 = 3; bytes 3 x 80 + 4 x 4 + 4 x 48 = 448.
TEST(BvhHandCounts, TwoFloorsWithLeafSize1AreThreeNodesFourLeavesDepthTwo) {
    const FlatBvh bvh = bvhOf(twoFloors(), 1);
    ASSERT_EQ(bvh.nodes.size(), 3u);
    EXPECT_EQ(bvh.stats.leaves, 4u);
    EXPECT_EQ(bvh.stats.depth, 2u);
    EXPECT_DOUBLE_EQ(bvh.stats.sahCost, 3.0);
    EXPECT_EQ(bvh.stats.bytes, 448u);
    const gpu::BvhNode& root = bvh.nodes[0];
    EXPECT_NE(root.min0.z, root.min1.z);  // one child per floor
    EXPECT_EQ(root.min0.z, root.max0.z);
    EXPECT_EQ(root.min1.z, root.max1.z);
}

using BvhHandKernels = VulkanTest;

// Walks and bytes by hand on the valley (leaf size 1). Child boxes: R's (triangle 0) x in [0,2],
// L's (triangle 1) x in [-2,0], both y in [0,4], z in [0,2].
//   ray 0 (from the left): enters L's box at 0.5, R's at 1.5 (test_tie_rule.cpp): L first, R
//     pushed; L hit at 1.5; R popped and its triangle tested (the stack holds references only):
//     1 node, 2 tests, 3 steps (root, L, R); the tie goes to L (1).
//   ray 1 (its mirror): R first: 0; the same counts.
//   ray 2, o = (-1, 2, 5), d = (0, 0, -1): x = -1 lies outside R's box, so only L's is entered;
//     L is z = -x = 1 there: t = 4 (Moller-Trumbore: det 8, u 0.25, v 0.5, t 32/8): 1 node, 1 test,
//     2 steps.
//   ray 3, o = (5, 2, 5) down the z axis: misses the scene box: nothing visited.
std::vector<gpu::Ray> walkRays() {
    std::vector<gpu::Ray> rays = valleyRays();
    rays.push_back(ray({-1, 2, 5}, {0, 0, -1}));
    rays.push_back(ray({5, 2, 5}, {0, 0, -1}));
    return rays;
}

TEST_F(BvhHandKernels, TheNearerChildFirstAndTheNodesLeavesTrianglesAndBytesOfEachRay) {
    for (std::uint32_t test : {gpu::kTriangleTestMollerTrumbore, gpu::kTriangleTestWatertight}) {
        SCOPED_TRACE(testName(test));
        const std::unique_ptr<Structure> s = bvhStructure(bvhOf(valley(), 1));
        s->setTriangleTest(test);
        const std::vector<gpu::Ray> rays = walkRays();
        const Answers a = answersOf(*vk_, *s, rays);
        expectAnswers(a, 0, {1, 1.5f, 1, 2, 3});
        expectAnswers(a, 1, {0, 1.5f, 1, 2, 3});
        expectAnswers(a, 2, {1, 4.0f, 1, 1, 2});
        expectAnswers(a, 3, {kNoHit, 0.0f, 0, 0, 0});
        // Branching bytes: 3 nodes visited x 80; 5 tests x (4-byte list entry + 48 bytes of
        // vertices); the ray read once (32) and the record written (16) per ray.
        const BranchingRun run = runBranching(*vk_, *s, rays, {64, 0, 1});
        const ArchitectureMetrics m = branchingMetrics(run.hits, run.activeLanes, run.laneSlots, s->costs());
        EXPECT_EQ(m.bytes.cells, 3u * 80u);
        EXPECT_EQ(m.bytes.triangleList, 5u * 4u);
        EXPECT_EQ(m.bytes.vertices, 5u * 48u);
        EXPECT_EQ(m.bytes.state, 4u * 32u);
        EXPECT_EQ(m.bytes.output, 4u * 16u);
        EXPECT_EQ(m.bytes.stack, 0u);  // branching keeps its stack in registers
        EXPECT_EQ(m.work.cellsTotal, 3u);
        EXPECT_EQ(m.work.stepsPerRayMax, 3u);
    }
}

// The far floor's node is popped after the near floor's hit (t = 4) and its children are clipped
// against it: both lie at t = 5, so neither is visited. Ray o = (0.75, 0.25, 5), d = (0, 0, -1)
// (the lower-right halves, triangles 0 and 2): root (the near floor's box entered at 4, the far
// one's at 5: near first, far pushed), near node (both leaves' boxes entered at 4: child 0 first),
// its two leaves (2 tests, triangle 2 hit at 4), far node (no child within [0, 4]): 3 nodes, 2
// tests, 5 steps. Taking the farther child first would test all four triangles in 7 steps.
TEST_F(BvhHandKernels, ANearerHitPrunesTheFartherSubtree) {
    for (std::uint32_t test : {gpu::kTriangleTestMollerTrumbore, gpu::kTriangleTestWatertight}) {
        SCOPED_TRACE(testName(test));
        const std::unique_ptr<Structure> s = bvhStructure(bvhOf(twoFloors(), 1));
        s->setTriangleTest(test);
        expectAnswers(answersOf(*vk_, *s, {ray({0.75f, 0.25f, 5}, {0, 0, -1})}), 0, {2, 4.0f, 3, 2, 5});
    }
}

// Multipass on the valley (leaf size 1), rays 0, 1 (as above) and ray 3 (misses the box), oracle
// threshold 0 (intersect whenever a ray waits). The BVH's traversal state is 144 bytes: 16 of walk
// state, which every pass moves, and the 128-byte stack (structures/bvh/bvh_layout.h), which stays in
// memory: its entries pushed and popped, 4 bytes each, are a category of their own.
struct MultipassHand {
    MultipassOptions options;
    std::vector<PassKind> sequence;
    std::uint64_t usefulTraverse, usefulIntersect, stencilWrites, structureReads, triangleReads, stackEntries;
    std::uint64_t lowerBound, stencilBytes, stateBytes, stackBytes;
};

MultipassOptions unroll(unsigned k, unsigned m, bool suppress) {
    MultipassOptions o;
    o.oracleThreshold = 0.0;
    o.traverseStepsPerPass = k;
    o.intersectionsPerPass = m;
    o.suppressFinishedReads = suppress;
    return o;
}

using K = PassKind;
// Per served ray: setup 32 (ray) + 16 (walk) + 16 (hit) = 64; traverse 32 + 16 + 16 + 16 (walk
// written) = 80; intersect 80 + 16 (hit written) = 96; write 16. Stack: rays 0 and 1 each push the
// farther leaf at the root and pop it after the first leaf's triangle (the pop after the second
// finds the stack empty and reads nothing): 4 entries, 16 bytes, whatever K and M.
// Stencil: one byte read per ray per traverse or intersect pass, one written per state change
// (setup changes all 3; then rays 0 and 1 change 4 times each: waiting, traversing, waiting, done).
const MultipassHand kHands[] = {
    // K = M = 1: T (root: push the farther leaf), T (first leaf: waiting), I (its triangle, hit,
    // pop: traversing), T (second leaf: waiting), I (its triangle, pop: empty, done).
    // useful: traverse 3 passes x 2 rays, intersect 2 x 2; node reads 2 (the root, per ray);
    // triangle reads 4. Lower bound: 3 steps / 1 + 2 tests / 1 = 5.
    // stencil 5 passes x 3 rays + 3 + 8 = 26; state 3 x 64 + 6 x 80 + 4 x 96 + 3 x 16 = 1104;
    {unroll(1, 1, false), {K::Setup, K::Traverse, K::Traverse, K::Intersect, K::Traverse, K::Intersect, K::Write},
     6, 4, 11, 2, 4, 4, 5, 26, 1104, 16},
    // K = M = 4, reads of the unrolled rest not suppressed: T (root, first leaf; 2 discarded node
    // reads), I (1 test, 3 discarded triangle reads; pop), T (second leaf; 3 discarded), I (1 + 3).
    // node reads 2 x (3 + 3) = 12; triangle reads 2 x (4 + 4) = 16. Lower bound 1 + 1 = 2.
    // stencil 4 x 3 + 11 = 23; state 3 x 64 + 4 x 80 + 4 x 96 + 48 = 944.
    {unroll(4, 4, false), {K::Setup, K::Traverse, K::Intersect, K::Traverse, K::Intersect, K::Write},
     4, 4, 11, 12, 16, 4, 2, 23, 944, 16},
    // The same, suppressed: only the root's read and the 4 tests' reads remain.
    {unroll(4, 4, true), {K::Setup, K::Traverse, K::Intersect, K::Traverse, K::Intersect, K::Write},
     4, 4, 11, 2, 4, 4, 2, 23, 944, 16},
};

TEST_F(BvhHandKernels, MultipassPassesEventsAndStackBytesByHand) {
    const std::unique_ptr<Structure> s = bvhStructure(bvhOf(valley(), 1));
    const std::vector<gpu::Ray> rays = {valleyRays()[0], valleyRays()[1], ray({5, 2, 5}, {0, 0, -1})};
    for (const MultipassHand& hand : kHands) {
        SCOPED_TRACE("K " + std::to_string(hand.options.traverseStepsPerPass) + " M " +
                     std::to_string(hand.options.intersectionsPerPass) +
                     (hand.options.suppressFinishedReads ? " suppressed" : ""));
        const MultipassRun gpuRun = runMultipass(*vk_, *s, rays, hand.options, {64, 0, 1});
        const MultipassResult cpuRun = simulateMultipass(*s, rays, hand.options);
        for (const MultipassCounts* c : {&gpuRun.counts, &cpuRun.counts}) {
            SCOPED_TRACE(c == &gpuRun.counts ? "kernels" : "simulator");
            EXPECT_EQ(c->sequence, hand.sequence);
            EXPECT_EQ(c->usefulTraverse, hand.usefulTraverse);
            EXPECT_EQ(c->usefulIntersect, hand.usefulIntersect);
            EXPECT_EQ(c->stencilWrites, hand.stencilWrites);
            EXPECT_EQ(c->structureReads, hand.structureReads);
            EXPECT_EQ(c->triangleReads, hand.triangleReads);
            EXPECT_EQ(c->stackEntries, hand.stackEntries);
        }
        expectRecord(gpuRun.hits[0], {1, 1.5f, 1, 2, 3}, "ray 0");
        expectRecord(gpuRun.hits[1], {0, 1.5f, 1, 2, 3}, "ray 1");
        expectRecord(gpuRun.hits[2], {kNoHit, 0.0f, 0, 0, 0}, "ray 2 (misses the box)");

        const ArchitectureMetrics m = multipassMetrics(gpuRun.hits, gpuRun.counts, hand.options, s->costs());
        EXPECT_EQ(m.passes, hand.sequence.size());
        EXPECT_EQ(m.passesLowerBound, hand.lowerBound);
        EXPECT_DOUBLE_EQ(m.simdEfficiency, double(hand.usefulTraverse + hand.usefulIntersect) /
                                               double((hand.sequence.size() - 2) * rays.size()));
        EXPECT_EQ(m.bytes.stencil, hand.stencilBytes);
        EXPECT_EQ(m.bytes.state, hand.stateBytes);
        EXPECT_EQ(m.bytes.stack, hand.stackBytes);
        EXPECT_EQ(m.bytes.cells, hand.structureReads * 80u);
        EXPECT_EQ(m.bytes.triangleList, hand.triangleReads * 4u);
        EXPECT_EQ(m.bytes.vertices, hand.triangleReads * 48u);
        EXPECT_EQ(m.bytes.output, 3u * 16u);
    }
}

}  // namespace
}  // namespace rtbench
