// Multipass final pass: every ray's hit record, in the branching kernel's format.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "multipass_common.glsl"

void main() {
    uint rayIndex = rtRayIndex();
    if (rayIndex >= rtRayCount()) return;
    RayCounters c = RayCounters(0u, 0u, 0u, 0u);
    if (instrument != 0u) c = rayCounters[rayIndex];
    rtWriteRecord(rayIndex, mpHitRecord(hitStates[rayIndex], c));
}
