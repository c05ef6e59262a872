// Multipass intersect pass: rays in state waiting test up to intersectionsPerPass triangles.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "multipass_common.glsl"

void main() {
    uint rayIndex = mpServedRay(kStateWaiting);
    if (rayIndex == kNoRay) return;
    MpEvents e = mpNoEvents();
    mpStateRay = rayIndex;
    RtTraversalState ts;
    MP_LOAD_STATE(ts, rayIndex);
    RayHitState hit = hitStates[rayIndex];
    uint state = mpIntersect(rays[rayIndex], ts, hit, e);
    MP_SAVE_STATE(ts, rayIndex);
    hitStates[rayIndex] = hit;
    if (state != kStateWaiting) stencil[rayIndex] = uint8_t(state);
    mpReport(rayIndex, kStateWaiting, state, e);
    mpFile(kStateWaiting, state, rayIndex);
}
