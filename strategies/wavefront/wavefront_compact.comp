// The wavefront's compaction: the made rays of the slots just shaded, in slot order, into the
// queue (rays, and parent, path and weight) at their workgroup's position from the scan plus
// the made rays before them in the workgroup. A stable compaction: the queue is the CPU's next
// generation ray for ray, where an atomic append (Laine et al. 2013) would order it by timing.
#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require  // gpu_layout.h's 64-bit counters
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_basic : require

#include "gpu_layout.h"

layout(local_size_x_id = kSpecWorkgroupSize) in;
layout(std430, set = 0, binding = kBindingRays) writeonly buffer QueueRayBuffer { Ray queueRays[]; };
layout(std430, set = 0, binding = kBindingPathQueue) writeonly buffer QueueBuffer { uvec4 queue[]; };
layout(std430, set = 0, binding = kBindingPathMade) readonly buffer MadeBuffer { Ray made[]; };
layout(std430, set = 0, binding = kBindingPathMadeInfo) readonly buffer MadeInfoBuffer { uvec4 madeInfo[]; };

#include "wavefront_common.glsl"

void main() {
    uint slot = wfInvocation();
    uvec4 info = slot < control.compactGroups.w ? madeInfo[slot] : uvec4(0u);
    uint total;
    uint position = groupSums[wfWorkgroup()] + wfWorkgroupExclusiveSum(info.x, total);
    if (info.x == 0u) return;
    queueRays[position] = made[slot];
    queue[position] = uvec4(info.yzw, 0u);
}
