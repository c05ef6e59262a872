#version 460
// The driver's own traversal (VK_KHR_ray_query) as a peer of rtbench's kernels: one invocation per
// ray traces the driver's acceleration structure (device/acceleration_structure.h) for the
// query's answer and writes the same hit record. No counters: what the driver does inside
// rayQueryProceedEXT is not ours to count.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_ray_query : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

#include "gpu_layout.h"

layout(local_size_x_id = kSpecWorkgroupSize) in;
layout(std430, set = 0, binding = kBindingRays) readonly buffer RayBuffer { Ray rays[]; };
layout(std430, set = 0, binding = kBindingHits) writeonly buffer HitBuffer { HitRecord hits[]; };
layout(push_constant) uniform PushConstants { RayQueryParams params; };

void main() {
    // 2D dispatch as every kernel's (kernels/bindings.glsl rtRayIndex).
    const uint i = gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x;
    if (i >= params.stream.x) return;
    const Ray ray = rays[i];
    HitRecord hit;
    hit.t = kNoHitT;
    hit.primitive = kNoHit;
    hit.u = 0.0;
    hit.v = 0.0;
    hit.cellsVisited = 0u;
    hit.trianglesTested = 0u;
    hit.traversalSteps = 0u;
    hit.pad = 0u;
    // rtbench's interval is [tMin, tMax) (gpu_layout.h kQuery*); the Vulkan spec's for a triangle
    // is open, tmin < t < tmax ("Ray Intersection Candidate Determination"): it starts at the
    // float below tMin (tMin >= 0: validateRays) and ends at tMax. An empty interval misses.
    const float tMin = ray.originTMin.w, tMax = ray.directionTMax.w;
    if (!(tMin < tMax)) {
        hits[i] = hit;
        return;
    }
    const float before = tMin > 0.0 ? uintBitsToFloat(floatBitsToUint(tMin) - 1u) : 0.0;
    // Opaque geometry: the driver commits every triangle it finds, so one call runs the whole walk.
    uint flags = gl_RayFlagsOpaqueEXT;
    if (params.stream.y == kQueryAny) flags |= gl_RayFlagsTerminateOnFirstHitEXT;
    rayQueryEXT query;
    rayQueryInitializeEXT(query, accelerationStructureEXT(params.topLevel), flags, 0xFFu, ray.originTMin.xyz, before,
                          ray.directionTMax.xyz, tMax);
    while (rayQueryProceedEXT(query)) {
    }
    if (rayQueryGetIntersectionTypeEXT(query, true) == gl_RayQueryCommittedIntersectionTriangleEXT) {
        hit.t = rayQueryGetIntersectionTEXT(query, true);
        hit.primitive = uint(rayQueryGetIntersectionPrimitiveIndexEXT(query, true));
        const vec2 uv = rayQueryGetIntersectionBarycentricsEXT(query, true);
        hit.u = uv.x;
        hit.v = uv.y;
    }
    hits[i] = hit;
}
