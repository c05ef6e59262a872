// The uniform grid's multipass per-ray work, Purcell et al. 2002 §3.2 and Christen 2005
// §5.4-5.6: ONE source for strategies/multipass/multipass_*.comp (through structure.glsl) and the CPU simulator
// (structures/uniform_grid/grid_reference.h). Each function is one kernel's work for one ray: it restores
// the ray's saved state, works, and returns the new state (the stencil byte); the caller saves
// it. MpEvents (kernels/traversal_common.glsl) reports what the accounting needs.
// Include after grid_traversal.glsl and traversal_common.glsl, with traverseStepsPerPass,
// intersectionsPerPass and suppressFinishedReads declared (specialization constants in GLSL,
// members in C++).

GridTraversalState mpSave(RtDda s, uint listPos) {
    GridTraversalState ts;
    ts.tMaxAxisLeave = vec4(s.tMaxAxis, s.tLeave);
    ts.cellList = uvec4(uint(s.cell.x), uint(s.cell.y), uint(s.cell.z), listPos);
    return ts;
}

// The saved voxel and its boundary distances, without the direction's step and spacing: all the
// intersect pass needs (its voxel's list and exit), with none of the three divisions.
RtDda mpRestorePosition(GridTraversalState ts) {
    RtDda s;
    s.cell = ivec3(int(ts.cellList.x), int(ts.cellList.y), int(ts.cellList.z));
    s.stepDir = ivec3(0);
    s.tMaxAxis = vec3(ts.tMaxAxisLeave);
    s.tDelta = vec3(0.0f);
    s.tLeave = ts.tMaxAxisLeave.w;
    return s;
}

// The whole walk's state: the saved position, and the step and spacing from the direction.
RtDda mpRestore(Ray ray, GridTraversalState ts) {
    RtDda s = mpRestorePosition(ts);
    vec3 d = vec3(ray.directionTMax);
    rtDdaDirection(d, rtInverseDirection(d), s);
    return s;
}

// After the current voxel's triangles (or an empty voxel): done when the nearest hit so far lies
// within the voxel or answers the query, else traverse on (the branching loop's termination test).
uint mpAfterVoxel(RtDda s, RayHitState hit) {
    return rtQueryDone(hit.primitive) || (hit.primitive != kNoHit && hit.t <= rtDdaVoxelExit(s)) ? kStateDoneHit
                                                                                                : kStateTraversing;
}

// Enters the DDA's current voxel: reads its triangle-list range.
uint mpEnterVoxel(RtDda s, RT_INOUT(uint) listPos, RayHitState hit, RT_INOUT(MpEvents) e) {
    e.visited += 1u;
    e.structureReads += 2u;
    uint cell = rtCellIndex(s.cell);
    uint first = cellOffsets[cell];
    uint end = cellOffsets[cell + 1u];
    listPos = first;
    if (first != end) return kStateWaiting;
    return mpAfterVoxel(s, hit);
}

// Setup pass (eye rays): clip to the grid box; rays that miss it are done at once.
uint mpSetup(Ray ray, RT_OUT(GridTraversalState) ts, RT_OUT(RayHitState) hit, RT_INOUT(MpEvents) e) {
    hit.t = ray.directionTMax.w;
    hit.primitive = kNoHit;
    hit.u = 0.0f;
    hit.v = 0.0f;
    RtDda s;
    if (!rtEnterGrid(ray, s)) {
        ts.tMaxAxisLeave = vec4(0.0f);
        ts.cellList = uvec4(0u);
        return kStateMissedBox;
    }
    uint listPos = 0u;
    uint state = mpEnterVoxel(s, listPos, hit, e);
    ts = mpSave(s, listPos);
    return state;
}

// Traverse pass: up to traverseStepsPerPass DDA steps (Purcell's loop unrolling, §4.2).
uint mpTraverse(Ray ray, RT_INOUT(GridTraversalState) ts, RayHitState hit, RT_INOUT(MpEvents) e) {
    RtDda s = mpRestore(ray, ts);
    uint listPos = ts.cellList.w;
    uint state = kStateTraversing;
    for (uint i = 0u; i < traverseStepsPerPass; ++i) {
        if (state == kStateTraversing) {
            e.steps += 1u;
            if (!rtDdaStep(s))
                state = mpDoneState(hit);
            else
                state = mpEnterVoxel(s, listPos, hit, e);
        } else if (suppressFinishedReads == 0u) {
            // Non-branching hardware runs the rest of the unrolled loop: it reads, then discards.
            ivec3 c = clamp(s.cell, ivec3(0), ivec3(int(params.resolution.x) - 1, int(params.resolution.y) - 1,
                                                    int(params.resolution.z) - 1));
            uint cell = rtCellIndex(c);
            e.structureReads += 2u;
            e.sink ^= cellOffsets[cell] ^ cellOffsets[cell + 1u];
        }
    }
    ts = mpSave(s, listPos);
    return state;
}

// The intersect pass's range is the current voxel's list.
uint mpTriangleAt(uint position) { return triangleList[position]; }
#include "../../kernels/multipass_intersect.glsl"

// Intersect pass: up to intersectionsPerPass triangles of the current voxel.
uint mpIntersect(Ray ray, RT_INOUT(GridTraversalState) ts, RT_INOUT(RayHitState) hit, RT_INOUT(MpEvents) e) {
    RtDda s = mpRestorePosition(ts);
    uint listPos = ts.cellList.w;
    e.structureReads += 1u;  // where the voxel's list ends
    uint listEnd = cellOffsets[rtCellIndex(s.cell) + 1u];
    uint state = mpIntersectRange(ray, listPos, listEnd, hit, e) ? mpAfterVoxel(s, hit) : kStateWaiting;
    ts.cellList.w = listPos;
    return state;
}
