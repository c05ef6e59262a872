// What the wavefront's kernels share (Laine, Karras & Aila 2013's wavefront path tracer, with
// stable queues): the control block (kernels/whole_path.glsl), the workgroup grids of their
// indirect dispatches, and a workgroup-wide prefix sum. Include after gpu_layout.h.
#ifndef RT_WAVEFRONT_COMMON_GLSL
#define RT_WAVEFRONT_COMMON_GLSL

#include "whole_path.glsl"

layout(constant_id = kSpecMaxGroupsX) const uint maxGroupsX = 65535u;

// Workgroups for `invocations`: one row when they fit maxGroupsX, else the fewest rows of the
// fewest groups (device/vulkan_context.h workgroupGrid).
uvec4 wfGroupsFor(uint invocations) {
    uint groups = (invocations + gl_WorkGroupSize.x - 1u) / gl_WorkGroupSize.x;
    uint y = max((groups + maxGroupsX - 1u) / maxGroupsX, 1u);
    return uvec4((groups + y - 1u) / y, y, 1u, 0u);
}

// This invocation's index and its workgroup's in a 2D grid (kernels/bindings.glsl rtRayIndex).
uint wfInvocation() { return gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x; }
uint wfWorkgroup() { return gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x; }

// Subgroup totals of one workgroup (at most 256 subgroups: the host refuses more).
shared uint wfSubgroupTotals[256];

// The sum of `value` over the workgroup's invocations before this one (by local index: a
// subgroup holds consecutive invocations, as on every driver rtbench knows; were it otherwise,
// the queues would leave the CPU's order and the run's generation checks would fail it), and
// the workgroup's total. Every invocation of the workgroup must call it.
uint wfWorkgroupExclusiveSum(uint value, out uint total) {
    uint inclusive = subgroupInclusiveAdd(value);
    if (gl_SubgroupInvocationID == gl_SubgroupSize - 1u) wfSubgroupTotals[gl_SubgroupID] = inclusive;
    barrier();  // every subgroup's total written before any is read
    uint before = 0u;
    total = 0u;
    for (uint s = 0u; s < gl_NumSubgroups; ++s) {
        uint t = wfSubgroupTotals[s];
        if (s < gl_SubgroupID) before += t;
        total += t;
    }
    barrier();  // the totals read before a next call overwrites them
    return before + inclusive - value;
}

#endif  // RT_WAVEFRONT_COMMON_GLSL
