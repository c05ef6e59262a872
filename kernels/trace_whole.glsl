// What the kernels that run a ray's whole traversal in one invocation share (branching, persistent
// threads): the structure's rtTrace with a subgroup ballot at every loop iteration, and the record
// it writes. Include after bindings.glsl.
#ifndef RT_TRACE_WHOLE_GLSL
#define RT_TRACE_WHOLE_GLSL

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

// Traces ray `rayIndex` and writes its record (bindings.glsl rtWriteRecord).
void rtTraceAndWrite(uint rayIndex) { rtWriteRecord(rayIndex, rtTrace(rays[rayIndex])); }

#endif  // RT_TRACE_WHOLE_GLSL
