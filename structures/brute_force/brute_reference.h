// CPU reference of brute force: its kernels' own source (kernels/ray_math.glsl,
// kernels/traversal_common.glsl and brute_traversal.glsl) compiled as C++
// (structures/shared_kernels.h).
#pragma once
#include "brute_layout.h"
#include "structures/shared_kernels.h"

namespace rtbench {

namespace bruteref {
using namespace glm;
using namespace rtbench::gpu;
#include "structures/shared_source_begin.h"
struct BruteKernels : KernelConstants {
    using RtTraversalState = BruteTraversalState;
    static constexpr std::uint64_t kTraversalStackBytes = 0;  // no node stack
    TracedArray<Triangle, MemoryKind::Vertices> triangles;
    TracedArray<std::uint32_t, MemoryKind::Vertices> packedTriangles;
    BruteParams params;
#include "../../kernels/ray_math.glsl"
#include "../../kernels/traversal_common.glsl"
#include "brute_traversal.glsl"
};
#include "structures/shared_source_end.h"
}  // namespace bruteref

}  // namespace rtbench
