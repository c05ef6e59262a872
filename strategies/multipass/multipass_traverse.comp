// Multipass traverse pass: rays in state traversing take up to traverseStepsPerPass traversal steps
// (grid: DDA steps).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "multipass_common.glsl"

void main() {
    uint rayIndex = mpServedRay(kStateTraversing);
    if (rayIndex == kNoRay) return;
    MpEvents e = mpNoEvents();
    mpStateRay = rayIndex;
    RtTraversalState ts;
    MP_LOAD_STATE(ts, rayIndex);
    uint state = mpTraverse(rays[rayIndex], ts, hitStates[rayIndex], e);
    MP_SAVE_STATE(ts, rayIndex);
    if (state != kStateTraversing) stencil[rayIndex] = uint8_t(state);
    mpReport(rayIndex, kStateTraversing, state, e);
    mpFile(kStateTraversing, state, rayIndex);
}
