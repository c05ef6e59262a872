// Multipass pass 0 (eye rays and traversal setup): every ray enters the structure (the grid: clipped
// to its box and placed in its first voxel) and is given its first state; compacted, the rays left
// active start the lists.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "multipass_common.glsl"

void main() {
    uint rayIndex = rtRayIndex();
    if (rayIndex >= rtRayCount()) return;
    MpEvents e = mpNoEvents();
    RtTraversalState ts;
    RayHitState hit;
    if (instrument != 0u) rayCounters[rayIndex] = RayCounters(0u, 0u, 0u, 0u);
    mpStateRay = rayIndex;
    uint state = mpSetup(rays[rayIndex], ts, hit, e);
    MP_SAVE_STATE(ts, rayIndex);
    hitStates[rayIndex] = hit;
    stencil[rayIndex] = uint8_t(state);
    mpReport(rayIndex, 0xFFu, state, e);
    mpFile(kNoRay, state, rayIndex);
}
