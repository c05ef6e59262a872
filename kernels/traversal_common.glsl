// What every structure's traversal shares: the empty hit record and the nearest-hit bookkeeping of
// the branching walks, the triangle test through the structure's `triangles` buffer, what the
// multipass per-ray work reports (MpEvents) and the hit record the write pass makes. ONE source
// for the kernels and the CPU references, included after kernels/ray_math.glsl and the
// structure's buffers, before its traversal.
#ifndef RT_TRAVERSAL_COMMON_GLSL
#define RT_TRAVERSAL_COMMON_GLSL

// Hooks for instrumentation at each iteration of a traversal's outer loop (voxels, BVH
// references) and of its triangle loop: kernels/branching.comp counts subgroup lanes there, the
// CPU reference logs the loop trips (methods/shared_source_begin.h); none elsewhere.
#ifndef RT_ON_OUTER
#define RT_ON_OUTER()
#endif
#ifndef RT_ON_INNER
#define RT_ON_INNER()
#endif

// A record with no hit and no work yet.
HitRecord rtEmptyRecord() {
    HitRecord h;
    h.t = kNoHitT;
    h.primitive = kNoHit;
    h.u = 0.0f;
    h.v = 0.0f;
    h.cellsVisited = 0u;
    h.trianglesTested = 0u;
    h.traversalSteps = 0u;
    h.pad = 0u;
    return h;
}

// The nearest hit so far: distance (the ray's tMax until a hit), barycentrics, triangle.
struct RtNearest {
    float t;
    float u;
    float v;
    uint primitive;
};

RtNearest rtNoHitYet(Ray ray) {
    RtNearest n;
    n.t = ray.directionTMax.w;
    n.u = 0.0f;
    n.v = 0.0f;
    n.primitive = kNoHit;
    return n;
}

// The configured test against triangle `tri` of the structure's `triangles`: updates (t, u, v)
// when it is hit in [tMin, t).
bool rtIntersectStored(RtTriangleRay r, uint tri, RT_INOUT(float) t, RT_INOUT(float) u, RT_INOUT(float) v) {
    return rtIntersect(r, vec3(triangles[tri].v0), vec3(triangles[tri].v1), vec3(triangles[tri].v2), t, u, v);
}

// Tests triangle `tri` and keeps it when it is hit nearer.
void rtTestTriangle(RtTriangleRay r, uint tri, RT_INOUT(RtNearest) n) {
    if (rtIntersectStored(r, tri, n.t, n.u, n.v)) n.primitive = tri;
}

// The record's hit fields from the nearest hit, if there is one.
void rtRecordNearest(RtNearest n, RT_INOUT(HitRecord) h) {
    if (n.primitive == kNoHit) return;
    h.t = n.t;
    h.primitive = n.primitive;
    h.u = n.u;
    h.v = n.v;
}

struct MpEvents {
    uint structureReads; // structure records read (grid: cell offsets; BVH: nodes)
    uint triangleReads;  // triangle-list entries read, each with the triangle's vertices
    uint visited;        // voxels entered
    uint tested;         // ray-triangle tests
    uint steps;          // traversal step attempts
    uint sink;           // xor of discarded reads: keeps the compiler from removing them
};

MpEvents mpNoEvents() {
    MpEvents e;
    e.structureReads = 0u;
    e.triangleReads = 0u;
    e.visited = 0u;
    e.tested = 0u;
    e.steps = 0u;
    e.sink = 0u;
    return e;
}

// Write pass: the hit record as the branching kernel writes it.
HitRecord mpHitRecord(RayHitState hit, RayCounters counters) {
    HitRecord h = rtEmptyRecord();
    if (hit.primitive != kNoHit) {
        h.t = hit.t;
        h.primitive = hit.primitive;
        h.u = hit.u;
        h.v = hit.v;
    }
    h.cellsVisited = counters.cellsVisited;
    h.trianglesTested = counters.trianglesTested;
    h.traversalSteps = counters.traversalSteps;
    return h;
}

// A multipass ray with nothing left to visit: done with its hit, or done without one.
uint mpDoneState(RayHitState hit) { return hit.primitive != kNoHit ? kStateDoneHit : kStateLeftGrid; }

// The read an unrolled intersect iteration makes for a ray already done, on hardware that cannot
// skip it (Purcell §4.2): a list entry and the vertices of triangle `tri`, read, then discarded.
void mpDiscardTriangleRead(uint tri, RT_INOUT(MpEvents) e) {
    e.triangleReads += 1u;
    e.sink ^= tri ^ floatBitsToUint(triangles[tri].v0.x) ^ floatBitsToUint(triangles[tri].v1.y) ^
              floatBitsToUint(triangles[tri].v2.z);
}

#endif  // RT_TRAVERSAL_COMMON_GLSL
