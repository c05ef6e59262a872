#version 450
// The control (issue 47 §1): a plain grid ray caster, what the branching kernel's speed is judged
// against. The same walk and Moller-Trumbore test as the branching kernel, operation for operation
// (structures/uniform_grid/grid_traversal.glsl, kernels/ray_math.glsl), without the harness's
// generality: each workgroup makes the camera rays of an 8 x 8 pixel tile, a voxel is a (first,
// count) pair, the device divides, a hit is 8 bytes (t, triangle), nothing is counted. Where the
// device's division is IEEE's (llvmpipe) its records are the CPU reference's.
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require  // kernels/gpu_layout.h declares 64-bit counters

#include "control_layout.h"

layout(local_size_x = 64) in;
layout(std430, binding = kControlBindingCells) readonly buffer Cells { uvec2 cells[]; };
layout(std430, binding = kControlBindingList) readonly buffer List { uint list[]; };
layout(std430, binding = kControlBindingTriangles) readonly buffer Triangles { Triangle triangles[]; };
layout(std430, binding = kControlBindingCamera) readonly buffer Camera { ControlCamera camera; float offsets[]; };
layout(std430, binding = kControlBindingHits) writeonly buffer Hits { uvec2 hits[]; };
layout(push_constant) uniform Push { ControlParams params; };

void main() {
    // The pixel: tile by tile (2D groups when there are more than maxComputeWorkGroupCount[0]).
    const uint tile = gl_WorkGroupID.x + gl_WorkGroupID.y * gl_NumWorkGroups.x;
    const uint px = (tile % params.image.z) * kControlTile + gl_LocalInvocationID.x % kControlTile;
    const uint py = (tile / params.image.z) * kControlTile + gl_LocalInvocationID.x / kControlTile;
    if (px >= params.image.x || py >= params.image.y) return;
    const vec3 o = camera.eye.xyz;
    precise vec3 d = camera.forward.xyz + offsets[px] * camera.right.xyz + offsets[params.image.x + py] * camera.down.xyz;
    precise vec3 invD = vec3(d.x != 0.0 ? 1.0 / d.x : 0.0, d.y != 0.0 ? 1.0 / d.y : 0.0, d.z != 0.0 ? 1.0 / d.z : 0.0);
    float tBest = kNoHitT;
    uint hit = kNoHit;
    // Clip to the grid box in its own frame (Kay & Kajiya), then set up the 3D-DDA (Amanatides & Woo).
    precise vec3 og = o - params.boundsMin.xyz;
    precise vec3 t0 = (vec3(0.0) - og) * invD;
    precise vec3 t1 = (params.gridExtent.xyz - og) * invD;
    float tEnter = 0.0, tLeave = kNoHitT;
    bool inside = true;
    ivec3 cell, stepDir;
    vec3 tMax, tDelta;
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0.0) {
            inside = inside && !(og[a] < 0.0 || og[a] > params.gridExtent[a]);
        } else {
            tEnter = max(tEnter, min(t0[a], t1[a]));
            tLeave = min(tLeave, max(t0[a], t1[a]));
        }
    }
    if (inside && tEnter <= tLeave) {
        precise vec3 entry = og + d * tEnter;
        for (int a = 0; a < 3; ++a) {
            precise float local = entry[a] * params.invCellSize[a];
            cell[a] = clamp(int(floor(local)), 0, int(params.resolution[a]) - 1);
            stepDir[a] = d[a] > 0.0 ? 1 : d[a] < 0.0 ? -1 : 0;
            precise float boundary = float(cell[a] + (d[a] > 0.0 ? 1 : 0)) * params.cellSize[a];
            tMax[a] = d[a] == 0.0 ? kNoHitT : (boundary - og[a]) * invD[a];
            tDelta[a] = d[a] == 0.0 ? kNoHitT : (d[a] > 0.0 ? params.cellSize[a] : -params.cellSize[a]) * invD[a];
        }
        while (true) {
            // Every triangle of the voxel; then stop where the nearest hit lies within it (Purcell §3.1.3).
            const uvec2 voxel = cells[uint(cell.x) + params.resolution.x * (uint(cell.y) + params.resolution.y * uint(cell.z))];
            for (uint i = voxel.x; i < voxel.x + voxel.y; ++i) {
                const Triangle tri = triangles[list[i]];
                precise vec3 e1 = tri.v1.xyz - tri.v0.xyz, e2 = tri.v2.xyz - tri.v0.xyz, s = o - tri.v0.xyz;
                precise vec3 p = vec3(d.y * e2.z - d.z * e2.y, d.z * e2.x - d.x * e2.z, d.x * e2.y - d.y * e2.x);
                precise float det = e1.x * p.x + e1.y * p.y + e1.z * p.z;
                if (det == 0.0) continue;
                precise float invDet = 1.0 / det;
                precise float u = (s.x * p.x + s.y * p.y + s.z * p.z) * invDet;
                if (u < 0.0 || u > 1.0) continue;
                precise vec3 q = vec3(s.y * e1.z - s.z * e1.y, s.z * e1.x - s.x * e1.z, s.x * e1.y - s.y * e1.x);
                precise float v = (d.x * q.x + d.y * q.y + d.z * q.z) * invDet;
                if (v < 0.0 || u + v > 1.0) continue;
                precise float t = (e2.x * q.x + e2.y * q.y + e2.z * q.z) * invDet;
                if (t < 0.0 || t >= tBest) continue;
                tBest = t;
                hit = list[i];
            }
            if (hit != kNoHit && tBest <= min(min(min(tMax.x, tMax.y), tMax.z), tLeave)) break;
            int axis = tMax.y < tMax.x ? 1 : 0;  // ties step the lowest axis
            if (tMax.z < tMax[axis]) axis = 2;
            if (tMax[axis] >= tLeave || stepDir[axis] == 0) break;
            cell[axis] += stepDir[axis];
            if (cell[axis] < 0 || cell[axis] >= int(params.resolution[axis])) break;
            precise float next = tMax[axis] + tDelta[axis];
            tMax[axis] = next;
        }
    }
    hits[py * params.image.x + px] = uvec2(floatBitsToUint(tBest), hit);
}
