// The wavefront's shading stage (Purcell et al. 2002 §3's shading kernel on the queue): slot j of
// the queue's slots (ray j / fan-out, its slot j % fan-out) gets the ray kernels/shading.glsl
// rtShade makes from that ray's hit, with a made flag, its parent, its path and its weight; each
// workgroup writes how many rays it made, for the scan. Nothing is appended here: the compaction
// puts the made rays in slot order, the CPU's (rays/shading.h ShadedRays).
#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require  // gpu_layout.h's 64-bit counters
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_basic : require

#include "gpu_layout.h"

layout(local_size_x_id = kSpecWorkgroupSize) in;
// ray_math.glsl's triangle tests read it; the shading pass tests no triangle.
layout(constant_id = kSpecTriangleTest) const uint triangleTest = kTriangleTestMollerTrumbore;
// rtDivide reads them: the shading pass always divides exactly, as the CPU does (kernels/shading.comp).
const uint nativeDivision = 0u;
const uint division = kDivisionDouble;

layout(std430, set = 0, binding = kBindingRays) readonly buffer QueueRayBuffer { Ray queueRays[]; };
layout(std430, set = 0, binding = kBindingHits) readonly buffer QueueHitBuffer { HitRecord queueHits[]; };
layout(std430, set = 0, binding = kBindingPathQueue) readonly buffer QueueBuffer { uvec4 queue[]; };
layout(std430, set = 0, binding = kBindingPathMade) writeonly buffer MadeBuffer { Ray made[]; };
layout(std430, set = 0, binding = kBindingPathMadeInfo) writeonly buffer MadeInfoBuffer { uvec4 madeInfo[]; };

#define RT_OUT(T) out T
#define RT_INOUT(T) inout T
#include "ray_math.glsl"
#include "shading.glsl"
#include "wavefront_common.glsl"

shared uint groupMade;

void main() {
    if (gl_LocalInvocationIndex == 0u) groupMade = 0u;
    barrier();  // the workgroup's count zeroed before any adds to it
    uint slot = wfInvocation();
    uint g = control.queue.y;
    if (slot < control.queue.z) {
        uint fanOut = control.passes[g].pass.z;
        uint parent = slot / fanOut;
        uint s = slot - parent * fanOut;
        uvec4 info = queue[parent];  // parent, path, weight bits
        Ray r;
        float w;
        bool ok = wpShade(g, queueRays[parent], queueHits[parent], info.y, s, uintBitsToFloat(info.z), r, w);
        if (ok) {
            made[slot] = r;
            atomicAdd(groupMade, 1u);
        }
        madeInfo[slot] = uvec4(ok ? 1u : 0u, parent, info.y * fanOut + s, floatBitsToUint(ok ? w : 0.0f));
    }
    barrier();  // every invocation's ray counted before the workgroup's total is written
    if (gl_LocalInvocationIndex == 0u) groupSums[wfWorkgroup()] = groupMade;
}
