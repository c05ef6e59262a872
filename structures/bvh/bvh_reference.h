// CPU reference of the BVH: its kernels' own source (kernels/ray_math.glsl,
// kernels/traversal_common.glsl and bvh_traversal.glsl) compiled as C++ (structures/shared_kernels.h),
// so its hits, per-ray counters and multipass events equal the GPU kernels' bit for bit.
#pragma once
#include "bvh_build.h"
#include "structures/shared_kernels.h"

namespace rtbench {

namespace bvhref {
using namespace glm;
using namespace rtbench::gpu;
#include "structures/shared_source_begin.h"
struct BvhKernels : KernelConstants {
    using RtTraversalState = BvhTraversalState;
    static constexpr std::uint64_t kTraversalStackBytes = sizeof(BvhTraversalState::stack);  // its node stack, at its end
    TracedArray<BvhNode, MemoryKind::Cells> nodes;
    TracedArray<std::uint32_t, MemoryKind::TriangleList> triangleList;
    TracedArray<Triangle, MemoryKind::Vertices> triangles;
    TracedArray<std::uint32_t, MemoryKind::Vertices> packedTriangles;
    BvhParams params;
    // The multipass walk's stack entries, which its kernels read and write in memory
    // (bvh_traversal.glsl): each reported to the thread's memory trace when there is one.
    static std::uint32_t mpStackRead(const BvhTraversalState& ts, std::uint32_t i) {
        if (MemoryTrace* trace = MemoryTrace::current()) trace->read(MemoryKind::Stack, &ts.stack[i], sizeof ts.stack[i]);
        return ts.stack[i];
    }
    static void mpStackWrite(BvhTraversalState& ts, std::uint32_t i, std::uint32_t value) {
        if (MemoryTrace* trace = MemoryTrace::current()) trace->write(MemoryKind::Stack, &ts.stack[i], sizeof ts.stack[i]);
        ts.stack[i] = value;
    }
#define MP_STACK_READ(ts, i) mpStackRead(ts, i)
#define MP_STACK_WRITE(ts, i, v) mpStackWrite(ts, i, v)
#include "../../kernels/ray_math.glsl"
#include "../../kernels/traversal_common.glsl"
#include "bvh_traversal.glsl"
#undef MP_STACK_READ
#undef MP_STACK_WRITE
};
#include "structures/shared_source_end.h"
}  // namespace bvhref

// The shared source over a flattened tree, float vertices.
bvhref::BvhKernels bvhKernels(const FlatBvh& bvh);

}  // namespace rtbench
