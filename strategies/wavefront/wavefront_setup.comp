// The wavefront's first kernel: the camera rays (generation 0) copied into the queue, each its
// own path and parent, weight 1; invocation 0 starts the control block at generation 0.
#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require  // gpu_layout.h's 64-bit counters
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_basic : require

#include "gpu_layout.h"

layout(local_size_x_id = kSpecWorkgroupSize) in;
layout(std430, set = 0, binding = kBindingRays) writeonly buffer QueueRayBuffer { Ray queueRays[]; };
layout(std430, set = 0, binding = kBindingPathQueue) writeonly buffer QueueBuffer { uvec4 queue[]; };

#include "wavefront_common.glsl"

void main() {
    uint i = wfInvocation();
    uint rays = uint(cameraRays.length());
    if (i == 0u) {
        uint slots = rays * wpFanOut(0u);
        control.traceGroups = wfGroupsFor(rays);
        control.slotGroups = wfGroupsFor(slots);
        control.queue = uvec4(rays, 0u, slots, 0u);
        control.compactGroups = uvec4(0u);
        control.limits.w = 0u;
    }
    if (i >= rays) return;
    queueRays[i] = cameraRays[i];
    queue[i] = uvec4(i, i, floatBitsToUint(1.0f), 0u);
}
