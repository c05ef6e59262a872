// The wavefront's scan, one workgroup: each shading workgroup's count of made rays becomes the
// queue position of its first (an exclusive prefix sum, in place), and the total the next
// generation's length; the control block moves on to it: its queue, the trace's and the next
// shading's workgroups, and the compaction's (the grid just shaded). A generation that would
// outgrow the queue or the slots is not traced or shaded: limits.w says so and the run fails.
#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require  // gpu_layout.h's 64-bit counters
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_basic : require

#include "gpu_layout.h"

layout(local_size_x_id = kSpecWorkgroupSize) in;

#include "wavefront_common.glsl"

void main() {
    uvec4 grid = control.slotGroups;
    uint groups = grid.x * grid.y;
    uint carry = 0u;
    for (uint base = 0u; base < groups; base += gl_WorkGroupSize.x) {
        uint i = base + gl_LocalInvocationIndex;
        uint count = i < groups ? groupSums[i] : 0u;
        uint chunk;
        uint before = wfWorkgroupExclusiveSum(count, chunk);
        if (i < groups) groupSums[i] = carry + before;
        carry += chunk;
    }
    if (gl_LocalInvocationIndex != 0u) return;
    uint rays = carry;
    uint g = control.queue.y + 1u;
    uint fanOut = wpFanOut(g);
    bool overflow = rays > control.limits.x || uint64_t(rays) * fanOut > uint64_t(control.limits.y);
    uint slots = overflow ? 0u : rays * fanOut;
    control.compactGroups = uvec4(grid.xyz, overflow ? 0u : control.queue.z);
    control.queue = uvec4(overflow ? 0u : rays, g, slots, 0u);
    control.traceGroups = wfGroupsFor(overflow ? 0u : rays);
    control.slotGroups = wfGroupsFor(slots);
    if (overflow) control.limits.w = 1u;
}
