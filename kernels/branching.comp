// Branching ray caster (Purcell et al. 2002 §3 in one kernel; the "branching architecture" of
// their §5): one invocation per ray runs the structure's whole traversal (rtTrace of
// methods/<structure>/structure.glsl) and writes its nearest hit.
#version 450
#extension GL_GOOGLE_include_directive : require

#include "bindings.glsl"

// SIMD efficiency (Aila & Laine 2009): at every iteration of the traversal's outer loop (voxels,
// nodes) and of its triangle loop, a ballot counts the lanes still in the loop against the
// subgroup size.
#define RT_LANE_BALLOT()                                                                       \
    if (instrument != 0u) {                                                                    \
        uvec4 lanes = subgroupBallot(true);                                                    \
        if (subgroupElect()) {                                                                 \
            atomicAdd(passCounters.counts[kCountActiveLanes], uint64_t(subgroupBallotBitCount(lanes))); \
            atomicAdd(passCounters.counts[kCountLaneSlots], uint64_t(gl_SubgroupSize));        \
        }                                                                                      \
    }
#define RT_ON_OUTER() RT_LANE_BALLOT()
#define RT_ON_INNER() RT_LANE_BALLOT()
#include "traversal_common.glsl"
#include "structure.glsl"

void main() {
    uint rayIndex = rtRayIndex();
    if (rayIndex >= rtRayCount()) return;
    HitRecord h = rtTrace(rays[rayIndex]);
    if (instrument == 0u) {
        h.cellsVisited = 0u;
        h.trianglesTested = 0u;
        h.traversalSteps = 0u;
    }
    hits[rayIndex] = h;
}
