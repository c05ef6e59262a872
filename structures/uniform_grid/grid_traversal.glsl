// Uniform-grid ray traversal: ONE source for the GPU kernels and the CPU reference.
// GLSL includes it (through structure.glsl) after declaring the buffers `cellOffsets`,
// `triangleList`, `triangles` and the push constant `params`; C++ includes it inside a struct with
// members of the same names (structures/uniform_grid/grid_reference.h), so both run the very same
// arithmetic, operation by operation (the rules are in kernels/ray_math.glsl, included first).
//
// Algorithms: slab clipping to the grid box (Kay & Kajiya 1986); 3D-DDA (Amanatides & Woo 1987);
// Purcell et al. 2002 §3.1.3: a hit beyond the current voxel does not end traversal (a nearer hit
// may lie in a later voxel). Such a hit is kept as the best candidate, and traversal ends in the
// first voxel whose exit lies beyond it.

// State of one ray's DDA walk (Amanatides & Woo 1987): the current voxel, the ray distance at
// which it crosses the next boundary on each axis (tMax), the distance between boundaries
// (tDelta), the step direction, and where the ray leaves the grid box (tLeave).
struct RtDda {
    ivec3 cell;
    ivec3 stepDir;
    vec3 tMaxAxis;
    vec3 tDelta;
    float tLeave;
};

// Step direction and boundary spacing per axis: derived from the direction alone, so multipass
// kernels recompute them each pass instead of saving them.
void rtDdaDirection(vec3 d, vec3 invD, RT_INOUT(RtDda) s) {
    vec3 cellSize = vec3(params.cellSize);
    for (int a = 0; a < 3; ++a) {
        if (d[a] > 0.0f) {
            s.stepDir[a] = 1;
            s.tDelta[a] = cellSize[a] * invD[a];
        } else if (d[a] < 0.0f) {
            s.stepDir[a] = -1;
            s.tDelta[a] = -cellSize[a] * invD[a];
        } else {
            s.stepDir[a] = 0;
            s.tDelta[a] = kNoHitT;
        }
    }
}

// Sets up the walk from the clipped entry distance tEnter; `o` is the origin in the grid's own
// frame (rtEnterGrid), where voxel c spans [c, c + 1] * cellSize.
RtDda rtDdaSetup(vec3 o, vec3 d, vec3 invD, float tEnter, float tLeave) {
    RtDda s;
    s.tLeave = tLeave;
    rtDdaDirection(d, invD, s);
    vec3 cellSize = vec3(params.cellSize);
    vec3 invCellSize = vec3(params.invCellSize);
    precise vec3 entry = o + d * tEnter;
    for (int a = 0; a < 3; ++a) {
        int last = int(params.resolution[a]) - 1;
        precise float local = entry[a] * invCellSize[a];
        int c = clamp(int(floor(local)), 0, last);
        s.cell[a] = c;
        if (d[a] > 0.0f) {
            precise float boundary = float(c + 1) * cellSize[a];
            s.tMaxAxis[a] = (boundary - o[a]) * invD[a];
        } else if (d[a] < 0.0f) {
            precise float boundary = float(c) * cellSize[a];
            s.tMaxAxis[a] = (boundary - o[a]) * invD[a];
        } else {
            s.tMaxAxis[a] = kNoHitT;
        }
    }
    return s;
}

// Distance at which the ray leaves the current voxel.
float rtDdaVoxelExit(RtDda s) { return min(min(min(s.tMaxAxis.x, s.tMaxAxis.y), s.tMaxAxis.z), s.tLeave); }

// Steps to the next voxel; false when the ray leaves the grid (or ends) instead.
// Ties (the ray crosses an edge or a corner) step the lowest axis first. Every step moves the
// voxel one cell along an axis the ray moves along, so a walk takes at most resX + resY + resZ
// steps; an axis it does not move along ends the walk (only a NaN distance, from inputs outside
// scene/scene_limits.h, could pick one, and would otherwise loop forever).
bool rtDdaStep(RT_INOUT(RtDda) s) {
    int axis = 0;
    if (s.tMaxAxis.y < s.tMaxAxis[axis]) axis = 1;
    if (s.tMaxAxis.z < s.tMaxAxis[axis]) axis = 2;
    if (s.tMaxAxis[axis] >= s.tLeave || s.stepDir[axis] == 0) return false;
    s.cell[axis] += s.stepDir[axis];
    if (s.cell[axis] < 0 || s.cell[axis] >= int(params.resolution[axis])) return false;
    precise float next = s.tMaxAxis[axis] + s.tDelta[axis];
    s.tMaxAxis[axis] = next;
    return true;
}

uint rtCellIndex(ivec3 c) {
    return uint(c.x) + params.resolution.x * (uint(c.y) + params.resolution.y * uint(c.z));
}

// Clips the ray to the grid box and sets up its walk from the first voxel; false when it misses.
// The walk runs in the grid's own frame, origin at the box's min corner: its positions are as
// large as the scene, not as its distance from the world origin, so a scene moved far away keeps
// the walk's precision (o - boundsMin is even exact while o lies within a factor 2 of boundsMin,
// Sterbenz). Distances along the ray are the same in both frames.
bool rtEnterGrid(Ray ray, RT_OUT(RtDda) s) {
    vec3 boxMin = vec3(params.boundsMin);
    precise vec3 o = vec3(ray.originTMin) - boxMin;
    precise vec3 boxMax = vec3(params.boundsMax) - boxMin;
    vec3 d = vec3(ray.directionTMax);
    vec3 invD = rtInverseDirection(d);
    float tEnter;
    float tLeave;
    if (!rtClipToBox(o, d, invD, ray.originTMin.w, ray.directionTMax.w, vec3(0.0f), boxMax, tEnter, tLeave))
        return false;
    s = rtDdaSetup(o, d, invD, tEnter, tLeave);
    return true;
}

// The branching ray caster (Purcell §3.1 in one loop): walk the grid, test every triangle of each
// non-empty voxel, stop in the first voxel whose exit lies at or beyond the nearest hit so far
// (an any-hit query: at its first hit).
HitRecord rtTrace(Ray ray) {
    HitRecord h = rtEmptyRecord();
    RtDda s;
    if (!rtEnterGrid(ray, s)) return h;
    RtTriangleRay r = rtTriangleRay(ray);
    RtNearest nearest = rtNoHitYet(ray);
    while (true) {
        RT_ON_OUTER();
        h.cellsVisited += 1u;
        uint cell = rtCellIndex(s.cell);
        uint first = cellOffsets[cell];
        uint end = cellOffsets[cell + 1u];
        for (uint i = first; i < end; ++i) {
            RT_ON_INNER();
            h.trianglesTested += 1u;
            if (rtTestTriangle(r, triangleList[i], nearest)) break;
        }
        if (rtQueryDone(nearest.primitive) || (nearest.primitive != kNoHit && nearest.t <= rtDdaVoxelExit(s))) break;
        h.traversalSteps += 1u;
        if (!rtDdaStep(s)) break;
    }
    rtRecordNearest(nearest, h);
    return h;
}
