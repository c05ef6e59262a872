// GPU-visible layout of the BVH: a binary tree whose node holds both children's boxes (Aila &
// Laine 2009), so one node fetch decides which children a ray enters; its buffers' binding slots,
// push-constant parameters and multipass state. Included by C++ and by GLSL after
// kernels/gpu_layout.h.
//
// Why this layout: a traversal step needs both child boxes to order the children front to back,
// so they share one 80-byte node (one fetch per inner node visited, the unit of the accounting).
// The child references are integers in their own uvec4 rather than bit patterns stored in the
// boxes' unused w lanes (Aila & Laine's 64-byte node): a small integer read as a float is a
// subnormal, which a device that flushes subnormals (lavapipe does) may turn to zero. Leaves are
// ranges of a triangle-index list, as the grid's voxels are, so both structures charge list
// entries and vertices alike; a leaf's range is packed into its reference.
#ifndef RTBENCH_BVH_LAYOUT_H
#define RTBENCH_BVH_LAYOUT_H

#include "../../kernels/layout_begin.h"

RTBENCH_CONST kBindingBvhNodes = kBindingStructure + 0u;         // BvhNode[innerNodes]; node 0 is the root
RTBENCH_CONST kBindingBvhTriangleList = kBindingStructure + 1u;  // uint[references]: triangle ids by leaf
RTBENCH_CONST kBindingBvhVertices = kBindingStructure + 2u;      // Triangle[triangleCount]
RTBENCH_CONST kBvhBindings = 3u;

// A child reference: an inner node's index (< 2^31); or a leaf, kBvhLeaf | (count - 1) << 24 |
// first list entry, so a leaf holds 1 to kBvhMaxLeafSize triangles and the list at most
// kBvhMaxReferences entries; or kBvhNone (the root of a tree that is a single leaf has one child).
// kBvhNone has the leaf bit set: it is never visited, since rtBvhChildren skips it before any test.
RTBENCH_CONST kBvhLeaf = 0x80000000u;
RTBENCH_CONST kBvhNone = 0xFFFFFFFFu;
RTBENCH_CONST kBvhMaxLeafSize = 128u;
RTBENCH_CONST kBvhMaxReferences = 0x01000000u;
// The traversal stack holds at most this many references; the builder is asked for at most this
// depth and the flattened tree is checked against it.
RTBENCH_CONST kBvhStackSize = 32u;

struct BvhNode {
    vec4 min0;        // byte 0: xyz child 0 box min, w unused
    vec4 max0;        // byte 16: xyz child 0 box max, w unused
    vec4 min1;        // byte 32: xyz child 1 box min, w unused
    vec4 max1;        // byte 48: xyz child 1 box max, w unused
    uvec4 children;   // byte 64: x, y = child 0, 1 references; z, w unused
};

// The tree's box, as push constants after StreamParams (16 + 32 bytes).
struct BvhParams {
    vec4 boundsMin;  // byte 0: xyz scene box min, w unused
    vec4 boundsMax;  // byte 16: xyz scene box max, w unused
};

// Multipass per-ray state, saved at the end of a pass and restored at the next: where the walk
// is and its stack of references still to visit (Purcell's architecture keeps all of it in
// memory between passes; the stack is its own bandwidth category).
struct BvhTraversalState {
    uvec4 walk;                  // byte 0: x = reference to visit next, y = stack size, z = list position, w = list end
    uint stack[kBvhStackSize];   // byte 16: references still to visit, the top at stack[walk.y - 1]
};

#ifdef __cplusplus
static_assert(sizeof(BvhNode) == 80);
static_assert(sizeof(BvhParams) == 32);
static_assert(sizeof(BvhTraversalState) == 16 + 4 * kBvhStackSize);
#endif
#include "../../kernels/layout_end.h"

#endif  // RTBENCH_BVH_LAYOUT_H
