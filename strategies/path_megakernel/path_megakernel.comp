// The path megakernel (Laine, Karras & Aila 2013's megakernel, against which they measured their
// wavefront): one invocation per camera ray traces it, then follows each path its hit starts (the
// first pass's slots, one after another) through every pass to the batch, shading between the
// traces in registers. One call site of the structure's rtTrace in one loop: the lanes of a
// subgroup trace together whatever generation each is at. Each path's batch ray and its record go
// to the slots of its path (made flag 0 where the path ended before the batch).
#version 450
#extension GL_GOOGLE_include_directive : require

#define RT_QUERY_PER_TRACE
#include "bindings.glsl"
#include "path_megakernel_layout.h"
#include "trace_whole.glsl"
#include "shading.glsl"

// The batch's query; every generation before it asks for the closest hit.
layout(constant_id = kSpecQuery) const uint batchQuery = kQueryClosest;
layout(std430, set = 0, binding = kBindingPathMade) writeonly buffer MadeBuffer { Ray batchRays[]; };
layout(std430, set = 0, binding = kBindingPathMadeInfo) writeonly buffer MadeInfoBuffer { uvec4 batchInfo[]; };

#include "whole_path.glsl"

void main() {
    uint camera = rtRayIndex();
    if (camera >= uint(cameraRays.length())) return;
    uint passes = control.limits.z;
    uint slots = passes == 0u ? 1u : control.passes[0].pass.z;  // paths this camera ray starts
    Ray cameraRay = cameraRays[camera];
    HitRecord cameraHit;
    Ray r = cameraRay;
    uint g = 0u;       // r's generation
    uint s = 0u;       // the first pass's next slot
    uint path = camera;
    float weight = 1.0f;
    bool tracing = true;
    while (tracing) {
        query = g == passes ? batchQuery : kQueryClosest;
        HitRecord h = rtTrace(r);
        if (instrument != 0u) rtCount(kCountPathRaysTraced, 1u);
        if (g == 0u) cameraHit = h;
        if (g == passes) {  // the batch: its ray and record at its path
            rtWriteRecord(path, h);
            batchRays[path] = r;
            batchInfo[path] = uvec4(1u, 0u, path, floatBitsToUint(weight));
        }
        // The next ray: this path's next generation, else the camera hit's next slot.
        Ray next;
        float nextWeight;
        bool more = g > 0u && g < passes && wpShade(g, r, h, path, 0u, weight, next, nextWeight);
        if (more) {
            g += 1u;
        } else {
            if (g > 0u && g < passes) batchInfo[path] = uvec4(0u);  // the path ended before the batch
            while (!more && passes > 0u && s < slots) {
                path = camera * slots + s;
                more = wpShade(0u, cameraRay, cameraHit, camera, s, 1.0f, next, nextWeight);
                if (!more) batchInfo[path] = uvec4(0u);  // the slot made no ray
                s += 1u;
            }
            g = 1u;
        }
        r = next;
        weight = nextWeight;
        tracing = more;
    }
}
