// The wavefront's trace stage: the branching kernel over the queue (one invocation per queued ray
// runs the structure's whole traversal), its length read from the control block, dispatched
// indirectly with the workgroups the stage before wrote.
#version 450
#extension GL_GOOGLE_include_directive : require

#include "bindings.glsl"
#include "trace_whole.glsl"
#include "wavefront_common.glsl"

void main() {
    uint rayIndex = rtRayIndex();
    if (rayIndex >= control.queue.x) return;
    rtTraceAndWrite(rayIndex);
}
