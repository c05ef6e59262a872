// BVH ray traversal: ONE source for the GPU kernels (through structure.glsl) and the CPU reference
// (structures/bvh/bvh_structure.cpp), included after kernels/ray_math.glsl and
// kernels/traversal_common.glsl; the buffers `nodes`, `triangleList`, `triangles` and the push
// constant `params` are declared by structure_layout.glsl in GLSL, members in C++.
//
// Algorithm: a per-ray stack walk of a binary BVH whose nodes hold both children's boxes (Aila &
// Laine 2009): at an inner node both child boxes are clipped against [tMin, nearest hit so far];
// the walk continues with the nearer child hit and pushes the other; a leaf's triangles are all
// tested (Moller-Trumbore, closest hit kept; an any-hit query ends at its first hit); then the next
// reference is popped. As in Aila &
// Laine's kernels the stack holds references only, so a popped subtree is not re-tested against
// a nearer hit found meanwhile: a popped inner node's child boxes are, a popped leaf's triangles
// are tested (and rejected by distance).
//
// The same walk serves both strategies: the branching kernel keeps its state (the reference to
// visit next, the stack) in local variables; the multipass kernels keep it, with the position in
// a leaf's list, in a BvhTraversalState saved in memory between passes. Both order and clip
// children with rtBvhChildren, and their hit records are identical, counters included.
// Counters: cellsVisited = inner nodes visited (each one 80-byte node read); traversalSteps =
// references visited (inner nodes and leaves).

bool rtBvhIsLeaf(uint ref) { return (ref & kBvhLeaf) != 0u; }
uint rtBvhLeafFirst(uint ref) { return ref & 0x00FFFFFFu; }
uint rtBvhLeafCount(uint ref) { return ((ref >> 24u) & 0x7Fu) + 1u; }

// Clips the ray to the scene box; false when the ray misses it (the walk then visits nothing).
bool rtBvhEnter(Ray ray) {
    vec3 o = vec3(ray.originTMin);
    vec3 d = vec3(ray.directionTMax);
    vec3 invD = rtInverseDirection(d);
    float tEnter;
    float tLeave;
    return rtClipToBox(o, d, invD, ray.originTMin.w, ray.directionTMax.w, vec3(params.boundsMin),
                       vec3(params.boundsMax), tEnter, tLeave);
}

// The children of inner node `n` the ray enters within [tMin, tBest], nearer first (child 0 on a
// tie): returns how many (0, 1 or 2) and sets `first` (and `second`).
uint rtBvhChildren(vec3 o, vec3 d, vec3 invD, float tMin, float tBest, BvhNode n, RT_OUT(uint) first,
                   RT_OUT(uint) second) {
    float enter0;
    float leave0;
    float enter1;
    float leave1;
    bool hit0 = n.children.x != kBvhNone &&
                rtClipToBox(o, d, invD, tMin, tBest, vec3(n.min0), vec3(n.max0), enter0, leave0);
    bool hit1 = n.children.y != kBvhNone &&
                rtClipToBox(o, d, invD, tMin, tBest, vec3(n.min1), vec3(n.max1), enter1, leave1);
    first = hit0 ? n.children.x : n.children.y;
    second = n.children.y;
    if (hit0 && hit1 && enter1 < enter0) {
        first = n.children.y;
        second = n.children.x;
    }
    return (hit0 ? 1u : 0u) + (hit1 ? 1u : 0u);
}

// The branching ray caster: the whole walk in one loop over local variables (the stack in
// registers or private memory), one outer iteration per reference visited, the triangle loop
// inside it for a leaf. A push beyond kBvhStackSize cannot happen (the builder bounds the depth);
// were it to, the walk would end there, as the multipass walk does.
HitRecord rtTrace(Ray ray) {
    HitRecord h = rtEmptyRecord();
    if (!rtBvhEnter(ray)) return h;
    RtTriangleRay r = rtTriangleRay(ray);
    vec3 invD = rtInverseDirection(r.d);
    RtNearest nearest = rtNoHitYet(ray);
    uint stack[kBvhStackSize];
    uint size = 0u;
    uint ref = 0u;  // the root, always an inner node
    while (true) {
        RT_ON_OUTER();
        h.traversalSteps += 1u;
        bool next = true;
        if (rtBvhIsLeaf(ref)) {
            uint first = rtBvhLeafFirst(ref);
            uint end = first + rtBvhLeafCount(ref);
            for (uint i = first; i < end; ++i) {
                RT_ON_INNER();
                h.trianglesTested += 1u;
                if (rtTestTriangle(r, triangleList[i], nearest)) break;
            }
            if (rtQueryDone(nearest.primitive)) break;
            next = false;
        } else {
            h.cellsVisited += 1u;
            uint first;
            uint second;
            uint entered = rtBvhChildren(r.o, r.d, invD, r.tMin, nearest.t, nodes[ref], first, second);
            if (entered == 2u) {
                if (size == kBvhStackSize) break;
                stack[size] = second;
                size += 1u;
            }
            if (entered > 0u) ref = first;
            else next = false;
        }
        if (!next) {  // pop
            if (size == 0u) break;
            size -= 1u;
            ref = stack[size];
        }
    }
    rtRecordNearest(nearest, h);
    return h;
}

// ---- multipass (Purcell et al. 2002 §3.2 on a BVH): traverse passes take walk steps until a
// leaf is reached (state waiting), intersect passes test its triangles and pop.
//
// The saved stack stays in memory: a pass moves the 16-byte walk state (ts.walk) and reads or
// writes only the stack entries it pops or pushes (e.stackEntries counts them), as a GPU kernel
// keeps a stack in memory. In the multipass kernels MP_STATE_RECORD is the served ray's record
// in the traversal-state buffer (strategies/multipass/multipass_common.glsl), which ts.walk alone is
// loaded from and saved to (MP_LOAD_STATE, MP_SAVE_STATE); the megakernel, which keeps the state
// in registers, defines MP_PRIVATE_STACK: the stack is an array of the invocation's own, as the
// branching walk's, outside the state it passes to mpTraverse and mpIntersect. Copying the whole
// 144-byte state in and out of every call instead made llvmpipe several times slower
// (docs/method.md). Compiled as C++, ts is the simulator's record, and BvhKernels's accessors
// (bvh_reference.h) report each entry to the memory trace.
#ifndef MP_STACK_READ
#ifdef MP_PRIVATE_STACK
uint mpPrivateStack[kBvhStackSize];
#define MP_STACK_READ(ts, i) mpPrivateStack[i]
#define MP_STACK_WRITE(ts, i, v) mpPrivateStack[i] = (v)
#elif defined(MP_STATE_RECORD)
#define MP_STACK_READ(ts, i) MP_STATE_RECORD.stack[i]
#define MP_STACK_WRITE(ts, i, v) MP_STATE_RECORD.stack[i] = (v)
#define MP_LOAD_STATE(ts, ray) ts.walk = traversalStates[ray].walk
#define MP_SAVE_STATE(ts, ray) traversalStates[ray].walk = ts.walk
#else  // kernels without a saved state compile the functions below but never call them
#define MP_STACK_READ(ts, i) ts.stack[i]
#define MP_STACK_WRITE(ts, i, v) ts.stack[i] = (v)
#endif
#endif

// Continues with the reference on top of the saved stack: traversing, or done when it is empty.
uint mpBvhPop(RT_INOUT(BvhTraversalState) ts, RayHitState hit, RT_INOUT(MpEvents) e) {
    if (ts.walk.y == 0u) return mpDoneState(hit);
    ts.walk.y -= 1u;
    ts.walk.x = MP_STACK_READ(ts, ts.walk.y);
    e.stackEntries += 1u;
    return kStateTraversing;
}

uint mpSetup(Ray ray, RT_OUT(BvhTraversalState) ts, RT_OUT(RayHitState) hit, RT_INOUT(MpEvents) e) {
    hit.t = ray.directionTMax.w;
    hit.primitive = kNoHit;
    hit.u = 0.0f;
    hit.v = 0.0f;
    ts.walk = uvec4(0u);  // the root, an empty stack (an entry is read only after a push wrote it)
    return rtBvhEnter(ray) ? kStateTraversing : kStateMissedBox;
}

// Traverse pass: up to traverseStepsPerPass walk steps (loop unrolling). A step visits an inner
// node, or enters a leaf (its triangles are then waiting).
uint mpTraverse(Ray ray, RT_INOUT(BvhTraversalState) ts, RayHitState hit, RT_INOUT(MpEvents) e) {
    vec3 o = vec3(ray.originTMin);
    vec3 d = vec3(ray.directionTMax);
    vec3 invD = rtInverseDirection(d);
    uint state = kStateTraversing;
    for (uint i = 0u; i < traverseStepsPerPass; ++i) {
        if (state == kStateTraversing) {
            e.steps += 1u;
            uint ref = ts.walk.x;
            if (rtBvhIsLeaf(ref)) {
                ts.walk.z = rtBvhLeafFirst(ref);
                ts.walk.w = rtBvhLeafFirst(ref) + rtBvhLeafCount(ref);
                state = kStateWaiting;
            } else {
                e.visited += 1u;
                e.structureReads += 1u;
                uint first;
                uint second;
                uint entered = rtBvhChildren(o, d, invD, ray.originTMin.w, hit.t, nodes[ref], first, second);
                if (entered == 2u && ts.walk.y == kBvhStackSize) {
                    state = mpDoneState(hit);  // cannot happen: see rtTrace
                } else {
                    if (entered == 2u) {
                        MP_STACK_WRITE(ts, ts.walk.y, second);
                        ts.walk.y += 1u;
                        e.stackEntries += 1u;
                    }
                    if (entered > 0u) ts.walk.x = first;
                    else state = mpBvhPop(ts, hit, e);
                }
            }
        } else if (suppressFinishedReads == 0u) {
            // Non-branching hardware runs the rest of the unrolled loop: it reads, then discards.
            // A whole node (the root: the walk's own may be a leaf or gone), as charged.
            BvhNode n = nodes[0u];
            e.structureReads += 1u;
            e.sink ^= n.children.x ^ n.children.y ^ n.children.z ^ n.children.w ^
                      floatBitsToUint(n.min0.x + n.min0.y + n.min0.z + n.max0.x + n.max0.y + n.max0.z + n.min1.x +
                                      n.min1.y + n.min1.z + n.max1.x + n.max1.y + n.max1.z);
        }
    }
    return state;
}

// The intersect pass's range is the current leaf's list.
uint mpTriangleAt(uint position) { return triangleList[position]; }
#include "../../kernels/multipass_intersect.glsl"

// Intersect pass: up to intersectionsPerPass triangles of the current leaf; after its last one
// the walk pops (traversing) or is done; an answered query is done.
uint mpIntersect(Ray ray, RT_INOUT(BvhTraversalState) ts, RT_INOUT(RayHitState) hit, RT_INOUT(MpEvents) e) {
    uint listPos = ts.walk.z;
    uint state = kStateWaiting;
    if (mpIntersectRange(ray, listPos, ts.walk.w, hit, e))
        state = rtQueryDone(hit.primitive) ? kStateDoneHit : mpBvhPop(ts, hit, e);
    ts.walk.z = listPos;
    return state;
}
