// Branching ray caster (Purcell et al. 2002 §3 in one kernel; the "branching architecture" of
// their §5): one invocation per ray runs the structure's whole traversal (rtTrace of
// structures/<structure>/structure.glsl) and writes its nearest hit.
#version 450
#extension GL_GOOGLE_include_directive : require

#include "bindings.glsl"
#include "trace_whole.glsl"

void main() {
    uint rayIndex = rtRayIndex();
    if (rayIndex >= rtRayCount()) return;
    rtTraceAndWrite(rayIndex);
}
