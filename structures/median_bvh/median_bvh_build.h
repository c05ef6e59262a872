// The median-split BVH (structure.type = "median_bvh"): each node splits its triangles at the
// median of their centroids along the centroid box's longest axis (pbrt-v4's
// SplitMethod::EqualCounts), with no cost model, into the same flat layout as Embree's SAH tree
// (structures/bvh/bvh_layout.h), so every strategy traces it with the BVH's kernels. A balanced
// tree of depth about log2(n / leaf size), built in O(n log n) on one thread: a cheaper build
// than Embree's binned SAH (structure.type = "bvh"), and a worse tree (results/trees; Embree's
// Morton build, quality = "low", is faster still and its tree better by the SAH).
#pragma once
#include "structures/bvh/bvh_build.h"

namespace rtbench {

// Deterministic: ties along the axis go by triangle id, each leaf's ids ascend. Throws
// rtbench::Error as buildBvh does (empty mesh, leaf size out of range, the layout's limits).
FlatBvh buildMedianBvh(const TriangleMesh& mesh, unsigned maxLeafSize);

}  // namespace rtbench
