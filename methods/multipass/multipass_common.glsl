// What every multipass kernel does around the structure's per-ray work: the stencil test (early
// exit of rays in other states, Purcell's early fragment kill), saving the new state, and counting.
#include "bindings.glsl"
#include "traversal_common.glsl"
#include "structure.glsl"

// Counts a served ray's events and new state. The oracle's counts are always kept (the host
// needs them to choose the next pass); the rest only when instrumented.
void mpReport(uint rayIndex, uint oldState, uint newState, MpEvents e) {
    rtCount(kCountTraversing, newState == kStateTraversing ? 1u : 0u);
    rtCount(kCountWaiting, newState == kStateWaiting ? 1u : 0u);
    if (instrument != 0u) {
        rtCount(kCountUsefulRays, 1u);
        rtCount(kCountStencilWrites, newState != oldState ? 1u : 0u);
        rtCount(kCountStructureReads, e.structureReads);
        rtCount(kCountTriangleReads, e.triangleReads);
        RayCounters c = rayCounters[rayIndex];
        c.cellsVisited += e.visited;
        c.trianglesTested += e.tested;
        c.traversalSteps += e.steps;
        rayCounters[rayIndex] = c;
    }
    // Keep the discarded reads of unrolled iterations alive (never true for a real ray index).
    if (e.sink == 0x9E3779B9u && rayIndex == 0xFFFFFFFFu) rayCounters[0].pad = e.sink;
}
