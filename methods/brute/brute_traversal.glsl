// Brute force: every ray against every triangle, nearest hit kept. ONE source for the kernels
// (through structure.glsl) and the CPU reference (methods/brute/brute_structure.cpp), included
// after kernels/ray_math.glsl and kernels/traversal_common.glsl; the buffer `triangles` and the
// push constant `params` are declared by structure_layout.glsl in GLSL, members in C++.
// The baseline every structure must beat, and all a scene of a few dozen triangles needs.

#ifndef RT_ON_OUTER
#define RT_ON_OUTER()
#endif
#ifndef RT_ON_INNER
#define RT_ON_INNER()
#endif

// Branching: one outer-loop iteration (the whole scene is one "cell"), its triangle loop over
// every triangle.
HitRecord rtTrace(Ray ray) {
    HitRecord h = rtEmptyRecord();
    vec3 o = vec3(ray.originTMin);
    vec3 d = vec3(ray.directionTMax);
    RtNearest nearest = rtNoHitYet(ray);
    RT_ON_OUTER();
    for (uint tri = 0u; tri < params.counts.x; ++tri) {
        RT_ON_INNER();
        h.trianglesTested += 1u;
        rtTestTriangle(o, d, ray.originTMin.w, tri, nearest);
    }
    rtRecordNearest(nearest, h);
    return h;
}

// Multipass: setup puts every ray in the waiting state at triangle 0; intersect passes test up to
// intersectionsPerPass triangles each; there is nothing to traverse.
uint mpDone(RayHitState hit) { return hit.primitive != kNoHit ? kStateDoneHit : kStateLeftGrid; }

uint mpSetup(Ray ray, RT_OUT(BruteTraversalState) ts, RT_OUT(RayHitState) hit, RT_INOUT(MpEvents) e) {
    hit.t = ray.directionTMax.w;
    hit.primitive = kNoHit;
    hit.u = 0.0f;
    hit.v = 0.0f;
    ts.next = uvec4(0u);
    return params.counts.x == 0u ? kStateLeftGrid : kStateWaiting;
}

// No ray is ever traversing: a ray given to this pass anyway is done.
uint mpTraverse(Ray ray, RT_INOUT(BruteTraversalState) ts, RayHitState hit, RT_INOUT(MpEvents) e) {
    return mpDone(hit);
}

uint mpIntersect(Ray ray, RT_INOUT(BruteTraversalState) ts, RT_INOUT(RayHitState) hit, RT_INOUT(MpEvents) e) {
    vec3 o = vec3(ray.originTMin);
    vec3 d = vec3(ray.directionTMax);
    uint next = ts.next.x;
    uint count = params.counts.x;
    uint state = kStateWaiting;
    for (uint i = 0u; i < intersectionsPerPass; ++i) {
        if (state == kStateWaiting) {
            uint tri = next;
            e.triangleReads += 1u;
            e.tested += 1u;
            if (rtIntersectTriangle(o, d, ray.originTMin.w, vec3(triangles[tri].v0), vec3(triangles[tri].v1),
                                    vec3(triangles[tri].v2), hit.t, hit.u, hit.v))
                hit.primitive = tri;
            next += 1u;
            if (next == count) state = mpDone(hit);
        } else if (suppressFinishedReads == 0u) {
            mpDiscardTriangleRead(count - 1u, e);
        }
    }
    ts.next.x = next;
    return state;
}
