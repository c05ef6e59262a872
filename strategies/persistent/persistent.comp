// Persistent threads with dynamic ray fetch (Aila & Laine 2009, "persistent while-while"): a fixed
// number of workgroups, launched once, whose subgroups take rays from one atomic counter a batch
// at a time until the stream is done; each lane runs its ray's whole traversal (rtTrace), as the
// branching kernel does. A batch is rays [base, base + raysPerFetch), run as raysPerFetch /
// subgroup-size rounds of consecutive rays, so its subgroup ballots are the branching kernel's.
// llvmpipe ends an invocation after 65,535 loop iterations, all loops together, and runs a
// workgroup's subgroups one after another, so one subgroup could take most of the stream: there a
// subgroup makes at most maxFetches fetches (persistentMaxFetches keeps it under the limit).
#version 450
#extension GL_GOOGLE_include_directive : require

#include "bindings.glsl"
#include "persistent_layout.h"
#include "trace_whole.glsl"

layout(constant_id = kSpecRaysPerFetch) const uint raysPerFetch = 32u;
layout(constant_id = kSpecMaxFetches) const uint maxFetches = 0u;  // 0: until the stream is done
layout(constant_id = kSpecPersistentWorkgroups) const uint workgroups = 0xffffffffu;

void main() {
    // Beyond 65,535 workgroups the grid is 2-D and may hold a few more than asked: they fetch nothing.
    if (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x >= workgroups) return;
    const uint rayCount = rtRayCount();
    bool fetching = true;
    for (uint fetches = 0u; fetching && (maxFetches == 0u || fetches < maxFetches); ++fetches) {
        // One fetch per subgroup: the elected lane takes the next batch; every lane sees its base.
        uint base = 0u;
        if (gl_SubgroupInvocationID == 0u)
            base = uint(min(atomicAdd(passCounters.counts[kCountRaysFetched], uint64_t(raysPerFetch)), uint64_t(rayCount)));
        base = subgroupMax(base);
        fetching = base < rayCount;
        uint traced = 0u;
        if (fetching) {
            for (uint round = 0u; round < raysPerFetch / gl_SubgroupSize; ++round) {
                uint rayIndex = base + round * gl_SubgroupSize + gl_SubgroupInvocationID;
                if (rayIndex < rayCount) {
                    rtTraceAndWrite(rayIndex);
                    traced += 1u;
                }
            }
        }
        rtCount(kCountRaysTraced, traced);
    }
}
