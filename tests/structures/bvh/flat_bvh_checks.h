// Checks of a tree in the BVH's flat layout (structures/bvh/bvh_layout.h) that hold whichever
// builder made it.
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "structures/bvh/bvh_build.h"

namespace rtbench {

// Walks the flattened tree: every triangle in exactly one leaf, every leaf's triangles inside the
// box its parent gives it, every leaf within the size asked for, the depth within the stack.
inline void expectWellFormed(const FlatBvh& bvh, const TriangleMesh& mesh, unsigned maxLeafSize) {
    std::vector<int> seen(mesh.triangles.size(), 0);
    std::uint64_t innerSeen = 0, leavesSeen = 0;
    struct Item { std::uint32_t ref; glm::vec3 lo, hi; unsigned depth; };
    std::vector<Item> todo;
    auto pushChildren = [&](std::uint32_t index, unsigned depth) {
        const gpu::BvhNode& n = bvh.nodes.at(index);
        todo.push_back({n.children.x, glm::vec3(n.min0), glm::vec3(n.max0), depth + 1});
        if (n.children.y != gpu::kBvhNone) todo.push_back({n.children.y, glm::vec3(n.min1), glm::vec3(n.max1), depth + 1});
    };
    pushChildren(0, 0);
    ++innerSeen;
    while (!todo.empty()) {
        const Item item = todo.back();
        todo.pop_back();
        ASSERT_LE(item.depth, gpu::kBvhStackSize);
        if (item.ref & gpu::kBvhLeaf) {
            ++leavesSeen;
            const std::uint32_t first = item.ref & 0x00FFFFFFu, count = ((item.ref >> 24) & 0x7Fu) + 1;
            EXPECT_LE(count, maxLeafSize);
            for (std::uint32_t i = first; i < first + count; ++i) {
                const std::uint32_t tri = bvh.triangleList.at(i);
                ++seen.at(tri);
                for (glm::uint v : {mesh.triangles[tri].x, mesh.triangles[tri].y, mesh.triangles[tri].z}) {
                    EXPECT_TRUE(glm::all(glm::greaterThanEqual(mesh.vertices[v], item.lo)) &&
                                glm::all(glm::lessThanEqual(mesh.vertices[v], item.hi)))
                        << "triangle " << tri << " outside its leaf's box";
                }
            }
        } else {
            ++innerSeen;
            const gpu::BvhNode& n = bvh.nodes.at(item.ref);
            // A child box lies within its parent's.
            EXPECT_TRUE(glm::all(glm::greaterThanEqual(glm::vec3(n.min0), item.lo)) &&
                        glm::all(glm::lessThanEqual(glm::vec3(n.max1), item.hi)));
            pushChildren(item.ref, item.depth);
        }
    }
    EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), std::ptrdiff_t(seen.size())) << "a triangle missing or repeated";
    EXPECT_EQ(innerSeen, bvh.nodes.size());
    EXPECT_EQ(innerSeen, bvh.stats.innerNodes);
    EXPECT_EQ(leavesSeen, bvh.stats.leaves);
    EXPECT_EQ(bvh.triangleList.size(), mesh.triangles.size());
}

}  // namespace rtbench
