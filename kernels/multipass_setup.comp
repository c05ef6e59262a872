// Multipass pass 0 (eye rays and traversal setup): every ray is clipped to the grid box, placed
// in its first voxel, and given its first state.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "multipass_common.glsl"

void main() {
    uint rayIndex = rtRayIndex();
    if (rayIndex >= params.resolution.w) return;
    MpEvents e = mpNoEvents();
    RayTraversalState ts;
    RayHitState hit;
    if (instrument != 0u) rayCounters[rayIndex] = RayCounters(0u, 0u, 0u, 0u);
    uint state = mpSetup(rays[rayIndex], ts, hit, e);
    traversalStates[rayIndex] = ts;
    hitStates[rayIndex] = hit;
    stencil[rayIndex] = uint8_t(state);
    mpReport(rayIndex, 0xFFu, state, e);
}
