// Branching ray caster (Purcell et al. 2002 §3 in one kernel; the "branching architecture" of
// their §5): one invocation per ray walks the uniform grid and writes its nearest hit.
#version 450
#extension GL_GOOGLE_include_directive : require

#include "gpu_layout.h"

layout(local_size_x_id = kSpecWorkgroupSize) in;
layout(constant_id = kSpecInstrument) const uint instrument = 1u;

layout(std430, set = 0, binding = kBindingRays) readonly buffer RayBuffer { Ray rays[]; };
layout(std430, set = 0, binding = kBindingCellOffsets) readonly buffer CellOffsetBuffer { uint cellOffsets[]; };
layout(std430, set = 0, binding = kBindingTriangleList) readonly buffer TriangleListBuffer { uint triangleList[]; };
layout(std430, set = 0, binding = kBindingVertices) readonly buffer TriangleBuffer { Triangle triangles[]; };
layout(std430, set = 0, binding = kBindingHits) writeonly buffer HitBuffer { HitRecord hits[]; };
layout(push_constant) uniform PushConstants { GridParams params; };

#define RT_OUT(T) out T
#define RT_INOUT(T) inout T
#include "grid_traversal.glsl"

void main() {
    // 2D dispatch: maxComputeWorkGroupCount[0] may be only 65535 groups.
    uint rayIndex = gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x;
    if (rayIndex >= params.resolution.w) return;
    HitRecord h = rtTraceGrid(rays[rayIndex]);
    if (instrument == 0u) {
        h.voxelsVisited = 0u;
        h.trianglesTested = 0u;
    }
    hits[rayIndex] = h;
}
