// Buffers, push constants and specialization constants of every kernel: one set layout (the
// slots of kernels/gpu_layout.h), so the host binds one descriptor set for all of them.
#extension GL_EXT_shader_8bit_storage : require
#extension GL_EXT_shader_explicit_arithmetic_types_int8 : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_ballot : require

#include "gpu_layout.h"

layout(local_size_x_id = kSpecWorkgroupSize) in;
layout(constant_id = kSpecInstrument) const uint instrument = 1u;
layout(constant_id = kSpecTraverseSteps) const uint traverseStepsPerPass = 1u;
layout(constant_id = kSpecIntersections) const uint intersectionsPerPass = 1u;
layout(constant_id = kSpecSuppress) const uint suppressFinishedReads = 0u;

layout(std430, set = 0, binding = kBindingRays) readonly buffer RayBuffer { Ray rays[]; };
layout(std430, set = 0, binding = kBindingCellOffsets) readonly buffer CellOffsetBuffer { uint cellOffsets[]; };
layout(std430, set = 0, binding = kBindingTriangleList) readonly buffer TriangleListBuffer { uint triangleList[]; };
layout(std430, set = 0, binding = kBindingVertices) readonly buffer TriangleBuffer { Triangle triangles[]; };
layout(std430, set = 0, binding = kBindingHits) writeonly buffer HitBuffer { HitRecord hits[]; };
layout(std430, set = 0, binding = kBindingStencil) buffer StencilBuffer { uint8_t stencil[]; };
layout(std430, set = 0, binding = kBindingTraversal) buffer TraversalBuffer { RayTraversalState traversalStates[]; };
layout(std430, set = 0, binding = kBindingHitState) buffer HitStateBuffer { RayHitState hitStates[]; };
layout(std430, set = 0, binding = kBindingRayCounters) buffer RayCounterBuffer { RayCounters rayCounters[]; };
layout(std430, set = 0, binding = kBindingPassCounters) buffer PassCounterBuffer { PassCounters passCounters; };
layout(push_constant) uniform PushConstants { GridParams params; };

#define RT_OUT(T) out T
#define RT_INOUT(T) inout T

// 2D dispatch: maxComputeWorkGroupCount[0] may be only 65535 groups.
uint rtRayIndex() { return gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x; }

// Adds a per-invocation count to a pass counter: one 64-bit atomic per subgroup.
void rtCount(uint slot, uint value) {
    uint total = subgroupAdd(value);
    if (subgroupElect() && total != 0u) atomicAdd(passCounters.counts[slot], uint64_t(total));
}
