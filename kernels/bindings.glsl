// Buffers, push constants and specialization constants of every kernel: the common slots of
// kernels/gpu_layout.h (a strategy declares its own slots' buffers), then the structure's own
// (structure_layout.glsl, found through the -I structures/<structure> CMake passes when it compiles
// a kernel for that structure). One set layout per structure, so the host binds one descriptor set
// for all of its kernels.
#extension GL_EXT_shader_8bit_storage : require
#extension GL_EXT_shader_explicit_arithmetic_types_int8 : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#extension GL_KHR_shader_subgroup_ballot : require

#include "gpu_layout.h"
#include "structure_layout.glsl"

layout(local_size_x_id = kSpecWorkgroupSize) in;
layout(constant_id = kSpecInstrument) const uint instrument = 1u;
layout(constant_id = kSpecTraverseSteps) const uint traverseStepsPerPass = 1u;
layout(constant_id = kSpecIntersections) const uint intersectionsPerPass = 1u;
layout(constant_id = kSpecSuppress) const uint suppressFinishedReads = 0u;
layout(constant_id = kSpecTriangleTest) const uint triangleTest = kTriangleTestMollerTrumbore;
layout(constant_id = kSpecVertexBits) const uint vertexBits = 0u;
layout(constant_id = kSpecLatticeOriginX) const float latticeOriginX = 0.0;
layout(constant_id = kSpecLatticeOriginY) const float latticeOriginY = 0.0;
layout(constant_id = kSpecLatticeOriginZ) const float latticeOriginZ = 0.0;
layout(constant_id = kSpecLatticeStep) const float latticeStep = 0.0;
#ifdef RT_QUERY_PER_TRACE
// A kernel that asks different rays different queries (the path megakernel: closest hits before
// the batch) sets it before each rtTrace, its own kSpecQuery constant naming the batch's.
uint query = kQueryClosest;
#else
layout(constant_id = kSpecQuery) const uint query = kQueryClosest;
#endif
layout(constant_id = kSpecNativeDivision) const uint nativeDivision = 0u;
layout(constant_id = kSpecDivision) const uint division = kDivisionDouble;

layout(std430, set = 0, binding = kBindingRays) readonly buffer RayBuffer { Ray rays[]; };
layout(std430, set = 0, binding = kBindingHits) writeonly buffer HitBuffer { HitRecord hits[]; };
// The same records as two 16-byte words each: word 2i is ray i's hit (t, primitive, u, v), the
// one store an uninstrumented kernel makes (llvmpipe stores a struct field by field, lane by lane).
layout(std430, set = 0, binding = kBindingHits) writeonly buffer HitWordBuffer { uvec4 hitWords[]; };
layout(std430, set = 0, binding = kBindingPassCounters) buffer PassCounterBuffer { PassCounters passCounters; };
layout(push_constant) uniform PushConstants {
    StreamParams stream;
    RtParams params;
};

#define RT_OUT(T) out T
#define RT_INOUT(T) inout T

// 2D dispatch: maxComputeWorkGroupCount[0] may be only 65535 groups.
uint rtRayIndex() { return gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x; }
uint rtRayCount() { return stream.stream.x; }

// Writes ray i's record: whole when instrumented; else the hit alone (t, primitive, u, v: what
// Embree's rtcIntersect1 answers too) in one 16-byte store, the work counters left as the
// instrumented run wrote them (the timed runs reuse its buffers; their hits are checked against it).
void rtWriteRecord(uint i, HitRecord h) {
    if (instrument != 0u)
        hits[i] = h;
    else
        hitWords[2u * i] = uvec4(floatBitsToUint(h.t), h.primitive, floatBitsToUint(h.u), floatBitsToUint(h.v));
}

// Adds a per-invocation count to a pass counter: one 64-bit atomic per subgroup.
void rtCount(uint slot, uint value) {
    uint total = subgroupAdd(value);
    if (subgroupElect() && total != 0u) atomicAdd(passCounters.counts[slot], uint64_t(total));
}

#include "ray_math.glsl"
