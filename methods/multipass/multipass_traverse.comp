// Multipass traverse pass: rays in state traversing take up to traverseStepsPerPass traversal steps
// (grid: DDA steps).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "multipass_common.glsl"

void main() {
    uint rayIndex = mpServedRay(kStateTraversing);
    if (rayIndex == kNoRay) return;
    MpEvents e = mpNoEvents();
    RtTraversalState ts = traversalStates[rayIndex];
    uint state = mpTraverse(rays[rayIndex], ts, hitStates[rayIndex], e);
    traversalStates[rayIndex] = ts;
    if (state != kStateTraversing) stencil[rayIndex] = uint8_t(state);
    mpReport(rayIndex, kStateTraversing, state, e);
    mpFile(kStateTraversing, state, rayIndex);
}
