// The shading pass (Purcell et al. 2002 §3's shading kernel): from a generation's rays and their
// hits, the rays of the next generation, each parent's params.pass.z slots by the rule of
// kernels/shading.glsl rtShade, the one source the CPU compiles too (rays/shading.h). Slot
// parent * fan-out + s is written whether or not it made a ray (made[] says), so the result is
// the same on every device and in the same order as the CPU's; the host keeps the made ones.
#version 450
#extension GL_GOOGLE_include_directive : require
// gpu_layout.h declares PassCounters with 64-bit counts, though this pass uses none.
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require

#include "gpu_layout.h"

layout(local_size_x_id = kSpecWorkgroupSize) in;
// ray_math.glsl's triangle tests read it; the shading pass tests no triangle.
layout(constant_id = kSpecTriangleTest) const uint triangleTest = kTriangleTestMollerTrumbore;
// rtDivide reads them: the shading pass always divides exactly, as the CPU does (either exact
// division gives the same bits).
const uint nativeDivision = 0u;
const uint division = kDivisionDouble;

layout(std430, set = 0, binding = kShadingBindingParents) readonly buffer ParentBuffer { Ray parents[]; };
layout(std430, set = 0, binding = kShadingBindingHits) readonly buffer HitBuffer { HitRecord hits[]; };
layout(std430, set = 0, binding = kShadingBindingPaths) readonly buffer PathBuffer { uint paths[]; };
layout(std430, set = 0, binding = kShadingBindingTriangles) readonly buffer TriangleBuffer { Triangle triangles[]; };
layout(std430, set = 0, binding = kShadingBindingRays) writeonly buffer RayBuffer { Ray rays[]; };
layout(std430, set = 0, binding = kShadingBindingMade) writeonly buffer MadeBuffer { uint made[]; };
layout(std430, set = 0, binding = kShadingBindingMaterialOf) readonly buffer MaterialOfBuffer { uint materialOf[]; };
layout(std430, set = 0, binding = kShadingBindingMaterials) readonly buffer MaterialBuffer { Material materials[]; };
layout(std430, set = 0, binding = kShadingBindingLights) readonly buffer LightBuffer { vec4 lights[]; };
layout(std430, set = 0, binding = kShadingBindingWeights) readonly buffer WeightBuffer { float weights[]; };
layout(std430, set = 0, binding = kShadingBindingMadeWeights) writeonly buffer MadeWeightBuffer { float madeWeights[]; };
layout(push_constant) uniform PushConstants { ShadingParams params; };

#define RT_OUT(T) out T
#define RT_INOUT(T) inout T
#include "ray_math.glsl"
#include "shading.glsl"

void main() {
    // 2D dispatch: maxComputeWorkGroupCount[0] may be only 65535 groups.
    uint slot = gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x;
    uint fanOut = params.pass.z;
    if (slot >= params.pass.x * fanOut) return;
    uint parent = slot / fanOut;
    HitRecord h = hits[parent];
    Ray r;
    r.originTMin = vec4(0.0f);
    r.directionTMax = vec4(0.0f);
    bool ok = false;
    float w = 0.0f;
    if (h.primitive != kNoHit) {
        Triangle t = triangles[h.primitive];
        uint s = slot - parent * fanOut;
        // Only a shadow pass reads its slot's light (a pass of no lights binds one unused).
        vec3 light = params.pass.y == kShadeShadow ? lights[s].xyz : vec3(0.0f);
        ok = rtShade(params, materials[materialOf[h.primitive]], light, t.v0.xyz, t.v1.xyz, t.v2.xyz, h.u, h.v,
                     parents[parent].directionTMax.xyz, paths[parent], s, weights[parent], r, w);
    }
    // A slot that made no ray is written as zeros (rtShade's `out` ray is undefined then).
    rays[slot] = ok ? r : Ray(vec4(0.0f), vec4(0.0f));
    made[slot] = ok ? 1u : 0u;
    madeWeights[slot] = ok ? w : 0.0f;
}
