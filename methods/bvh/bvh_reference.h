// CPU reference of the BVH: its kernels' own source (kernels/ray_math.glsl,
// kernels/traversal_common.glsl and bvh_traversal.glsl) compiled as C++ (methods/shared_kernels.h),
// so its hits, per-ray counters and multipass events equal the GPU kernels' bit for bit.
#pragma once
#include "bvh_build.h"
#include "methods/shared_kernels.h"

namespace rtbench {

namespace bvhref {
using namespace glm;
using namespace rtbench::gpu;
#include "methods/shared_source_begin.h"
struct BvhKernels : KernelConstants {
    using RtTraversalState = BvhTraversalState;
    static constexpr std::uint64_t kTraversalStackBytes = sizeof(BvhTraversalState::stack);  // its node stack, at its end
    TracedArray<BvhNode, MemoryKind::Cells> nodes;
    TracedArray<std::uint32_t, MemoryKind::TriangleList> triangleList;
    TracedArray<Triangle, MemoryKind::Vertices> triangles;
    TracedArray<std::uint32_t, MemoryKind::Vertices> packedTriangles;
    BvhParams params;
#include "../../kernels/ray_math.glsl"
#include "../../kernels/traversal_common.glsl"
#include "bvh_traversal.glsl"
};
#include "methods/shared_source_end.h"
}  // namespace bvhref

// The shared source over a flattened tree, float vertices.
bvhref::BvhKernels bvhKernels(const FlatBvh& bvh);

}  // namespace rtbench
