// GPU-visible layout of brute force (every ray against every triangle): its one buffer's binding
// slot, its push-constant parameters and its multipass state. Included by C++ and by GLSL after
// kernels/gpu_layout.h.
#ifndef RTBENCH_BRUTE_LAYOUT_H
#define RTBENCH_BRUTE_LAYOUT_H

#include "../../kernels/layout_begin.h"

RTBENCH_CONST kBindingBruteTriangles = kBindingStructure + 0u;  // Triangle[triangleCount]
RTBENCH_CONST kBruteBindings = 1u;

struct BruteParams {
    uvec4 counts;  // byte 0: x = triangle count, yzw unused
};

// Multipass per-ray state: the next triangle to test.
struct BruteTraversalState {
    uvec4 next;  // byte 0: x = index of the next triangle, yzw unused
};

#ifdef __cplusplus
static_assert(sizeof(BruteParams) == 16);
static_assert(sizeof(BruteTraversalState) == 16);
#endif
#include "../../kernels/layout_end.h"

#endif  // RTBENCH_BRUTE_LAYOUT_H
