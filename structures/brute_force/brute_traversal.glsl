// Brute force: every ray against every triangle, nearest hit kept. ONE source for the kernels
// (through structure.glsl) and the CPU reference (structures/brute_force/brute_structure.cpp), included
// after kernels/ray_math.glsl and kernels/traversal_common.glsl; the buffer `triangles` and the
// push constant `params` are declared by structure_layout.glsl in GLSL, members in C++.
// The baseline every structure must beat, and all a scene of a few dozen triangles needs.

// Branching: one outer-loop iteration (the whole scene is one "cell"), its triangle loop over
// every triangle.
HitRecord rtTrace(Ray ray) {
    HitRecord h = rtEmptyRecord();
    RtTriangleRay r = rtTriangleRay(ray);
    RtNearest nearest = rtNoHitYet(ray);
    RT_ON_OUTER();
    for (uint tri = 0u; tri < params.counts.x; ++tri) {
        RT_ON_INNER();
        h.trianglesTested += 1u;
        if (rtTestTriangle(r, tri, nearest)) break;
    }
    rtRecordNearest(nearest, h);
    return h;
}

// Multipass: setup puts every ray in the waiting state at triangle 0; intersect passes test up to
// intersectionsPerPass triangles each; there is nothing to traverse.
uint mpSetup(Ray ray, RT_OUT(BruteTraversalState) ts, RT_OUT(RayHitState) hit, RT_INOUT(MpEvents) e) {
    hit.t = ray.directionTMax.w;
    hit.primitive = kNoHit;
    hit.u = 0.0f;
    hit.v = 0.0f;
    ts.next = uvec4(0u);
    return params.counts.x == 0u ? kStateLeftStructure : kStateWaiting;
}

// No ray is ever traversing: a ray given to this pass anyway is done.
uint mpTraverse(Ray ray, RT_INOUT(BruteTraversalState) ts, RayHitState hit, RT_INOUT(MpEvents) e) {
    return mpDoneState(hit);
}

// The intersect pass's range is every triangle, by index.
uint mpTriangleAt(uint position) { return position; }
#include "../../kernels/multipass_intersect.glsl"

uint mpIntersect(Ray ray, RT_INOUT(BruteTraversalState) ts, RT_INOUT(RayHitState) hit, RT_INOUT(MpEvents) e) {
    uint next = ts.next.x;
    uint state = mpIntersectRange(ray, next, params.counts.x, hit, e) ? mpDoneState(hit) : kStateWaiting;
    ts.next.x = next;
    return state;
}
