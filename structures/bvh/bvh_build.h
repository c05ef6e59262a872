// Builds the BVH on the CPU with Embree's BVH builder (rtcBuildBVH, Embree 3: binned SAH for
// quality "medium", Morton codes for "low") and flattens it into the GPU layout of bvh_layout.h.
// The flattened tree is deterministic: nodes in depth-first order from the root (child 0 first),
// each leaf's triangle ids in ascending order, whatever order Embree's threads produced them in.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "bvh_layout.h"
#include "scene/mesh.h"

namespace rtbench {

struct BvhBuildOptions {
    unsigned maxLeafSize = 4;           // triangles per leaf at most (1 .. kBvhMaxLeafSize)
    std::string quality = "medium";     // "medium": binned SAH; "low": Morton (faster build, worse tree)
    float traversalCost = 1.0f;         // SAH cost of visiting a node ...
    float intersectionCost = 1.0f;      // ... and of one ray-triangle test
    std::string embreeConfig;           // rtcNewDevice's config string (e.g. "isa=avx2, threads=1")
};

struct BvhStats {
    std::uint64_t innerNodes = 0, leaves = 0, references = 0;
    unsigned depth = 0;             // edges from the root to the deepest leaf
    unsigned largestLeaf = 0;
    double sahCost = 0.0;           // sum over inner nodes of Ct * area / root area + over leaves of Ci * n * area / root area
    std::uint64_t bytes = 0;        // nodes + triangle list + triangle vertices
    double buildMs = 0.0;
};

struct FlatBvh {
    gpu::BvhParams params{};                  // the scene box
    std::vector<gpu::BvhNode> nodes;          // nodes[0] is the root
    std::vector<std::uint32_t> triangleList;  // leaves' triangle ids
    std::vector<gpu::Triangle> triangles;     // vertices per triangle
    VertexLattice lattice;                    // the mesh's: bits != 0, the device stores them packed
    BvhStats stats;
};

// Throws rtbench::Error when the mesh is empty, Embree fails, or the tree exceeds the layout's
// limits (depth over kBvhStackSize, more than kBvhMaxReferences list entries).
FlatBvh buildBvh(const TriangleMesh& mesh, const BvhBuildOptions& options);

}  // namespace rtbench
