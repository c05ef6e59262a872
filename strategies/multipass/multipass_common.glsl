// What every multipass kernel does around the structure's per-ray work: the stencil test (early
// exit of rays in other states, Purcell's early fragment kill), saving the new state, and counting.
#include "bindings.glsl"
#include "multipass_layout.h"
#include "traversal_common.glsl"
// The per-ray state kept between passes, in multipass's own slots (kernels/gpu_layout.h).
layout(std430, set = 0, binding = kBindingStencil) buffer StencilBuffer { uint8_t stencil[]; };
layout(std430, set = 0, binding = kBindingTraversal) buffer TraversalBuffer { RtTraversalState traversalStates[]; };
layout(std430, set = 0, binding = kBindingHitState) buffer HitStateBuffer { RayHitState hitStates[]; };
layout(std430, set = 0, binding = kBindingRayCounters) buffer RayCounterBuffer { RayCounters rayCounters[]; };

// The ray this invocation serves; a structure may keep part of its saved state in memory and
// address it there (the BVH's stack: structures/bvh/bvh_traversal.glsl).
uint mpStateRay = 0u;
#define MP_STATE_RECORD traversalStates[mpStateRay]
#include "structure.glsl"
// A structure that keeps none of its state in memory moves the whole record.
#ifndef MP_LOAD_STATE
#define MP_LOAD_STATE(ts, ray) ts = traversalStates[ray]
#define MP_SAVE_STATE(ts, ray) traversalStates[ray] = ts
#endif

// strategy.control = "device": the passes serve the rays of compacted lists, which the oracle
// kernel (multipass_oracle.comp) keeps in its control block, instead of the stream's stencil.
layout(constant_id = kSpecCompact) const uint compact = 0u;
layout(constant_id = kSpecListPartitions) const uint listPartitions = 1u;
layout(std430, set = 0, binding = kBindingRayLists) buffer RayListBuffer { uint rayLists[]; };
layout(std430, set = 0, binding = kBindingPassControl) buffer PassControlBuffer {
    PassControl control;
    PassLogEntry passLog[];
};

const uint kNoRay = 0xFFFFFFFFu;

// Partition p of ray list l (strategy.list_partitions): its length in the control block, and its
// entry i. Macros, not functions, so that the SPIR-V (and the instruction estimate) is as written out.
#define MP_LIST_LENGTH(l, p) control.lists[(l) * kMaxListPartitions + (p)].count
#define MP_LIST_ENTRY(l, p, i) rayLists[((l) * listPartitions + (p)) * rtRayCount() + (i)]

// The list a pass over rays in `state` reads, and the other list of its pair.
uint mpCurrentList(uint state) { return state == kStateTraversing ? control.current.x : 2u + control.current.y; }
uint mpOtherList(uint state) { return state == kStateTraversing ? 1u - control.current.x : 3u - control.current.y; }

// The ray this invocation serves in a pass over the rays in `state`, or kNoRay: with the stencil,
// its own ray when the ray's state byte says `state` (the stencil test, Purcell's early fragment
// kill); compacted, the entry of the state's current list, its partitions read in order.
uint mpServedRay(uint state) {
    uint slot = rtRayIndex();
    if (compact == 0u) return slot < rtRayCount() && uint(stencil[slot]) == state ? slot : kNoRay;
    uint list = mpCurrentList(state);
    for (uint p = 0u; p < listPartitions; ++p) {
        uint n = MP_LIST_LENGTH(list, p);
        if (slot < n) return MP_LIST_ENTRY(list, p, slot);
        slot -= n;
    }
    return kNoRay;
}

// The partition of a list this workgroup appends to: the dispatch's workgroups in listPartitions
// equal runs, one per partition (strategy.list_partitions). Workgroups that run side by side (on
// lavapipe, each worker thread takes a contiguous run of them) then append to different lengths,
// and the next pass, reading the partitions in order, hands each run the rays the same run filed.
uint mpPartition() {
    uint64_t group = uint64_t(gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x);
    uint64_t groups = uint64_t(gl_NumWorkGroups.x * gl_NumWorkGroups.y);
    return uint(group * uint64_t(listPartitions) / groups);
}

// Stream compaction by subgroup ballot: the subgroup's rays that `want` take consecutive entries of
// the workgroup's partition of `list`, claimed with one atomic per subgroup. The ballot, the
// election and the broadcast must see the same active lanes (the lanes reconverge after
// `if (subgroupElect())`, which Vulkan does not promise without
// VK_KHR_shader_maximal_reconvergence): a device that broke it would file rays on top of each
// other, and the run would fail (hits against branching's, the lists' overflow check).
void mpAppend(uint list, bool want, uint rayIndex) {
    uvec4 ballot = subgroupBallot(want);
    uint n = subgroupBallotBitCount(ballot);
    if (n == 0u) return;
    uint base = 0u;
    uint p = mpPartition();
    if (subgroupElect()) base = atomicAdd(MP_LIST_LENGTH(list, p), n);
    base = subgroupBroadcastFirst(base);
    uint entry = base + subgroupBallotExclusiveBitCount(ballot);
    // else: overflow, the oracle ends the loop
    if (want && entry < rtRayCount()) MP_LIST_ENTRY(list, p, entry) = rayIndex;
}

// Compacted: files a ray the pass over `passState` leaves active. A ray still in the pass's state
// goes to the other list of that pair (the pass reads the current one); a ray now in the other
// state joins that state's current list. Setup (passState kNoRay) fills both current lists.
void mpFile(uint passState, uint newState, uint rayIndex) {
    if (compact == 0u) return;
    mpAppend(passState == kStateTraversing ? mpOtherList(kStateTraversing) : mpCurrentList(kStateTraversing),
             newState == kStateTraversing, rayIndex);
    mpAppend(passState == kStateWaiting ? mpOtherList(kStateWaiting) : mpCurrentList(kStateWaiting),
             newState == kStateWaiting, rayIndex);
}

// Counts a served ray's events and new state. The oracle's counts are kept whenever the host's
// oracle needs them (it chooses the next pass from them); compacted, the oracle kernel reads the
// list lengths and they are kept only when instrumented, as a check. The rest only when instrumented.
void mpReport(uint rayIndex, uint oldState, uint newState, MpEvents e) {
    if (compact == 0u || instrument != 0u) {
        rtCount(kCountTraversing, newState == kStateTraversing ? 1u : 0u);
        rtCount(kCountWaiting, newState == kStateWaiting ? 1u : 0u);
    }
    if (instrument != 0u) {
        rtCount(kCountUsefulRays, 1u);
        rtCount(kCountStencilWrites, newState != oldState ? 1u : 0u);
        rtCount(kCountStructureReads, e.structureReads);
        rtCount(kCountTriangleReads, e.triangleReads);
        rtCount(kCountStackEntries, e.stackEntries);
        RayCounters c = rayCounters[rayIndex];
        c.cellsVisited += e.visited;
        c.trianglesTested += e.tested;
        c.traversalSteps += e.steps;
        rayCounters[rayIndex] = c;
    }
    // Keep the discarded reads of unrolled iterations alive (never true for a real ray index).
    if (e.sink == 0x9E3779B9u && rayIndex == 0xFFFFFFFFu) rayCounters[0].pad = e.sink;
}
