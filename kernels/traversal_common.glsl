// What every structure's traversal shares: the empty hit record and the nearest-hit bookkeeping of
// the branching walks, the triangle test through the structure's vertex buffer (float or packed), what the
// multipass per-ray work reports (MpEvents) and the hit record the write pass makes. ONE source
// for the kernels and the CPU references, included after kernels/ray_math.glsl and the
// structure's buffers, before its traversal.
#ifndef RT_TRAVERSAL_COMMON_GLSL
#define RT_TRAVERSAL_COMMON_GLSL

// Hooks for instrumentation at each iteration of a traversal's outer loop (voxels, BVH
// references) and of its triangle loop: strategies/branching/branching.comp counts subgroup lanes there, the
// CPU reference logs the loop trips (structures/shared_source_begin.h); none elsewhere.
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

// A packed vertex: its lattice point, origin + q * step. The product is exact (q < 2^16, step a
// power of two), so the one rounding of the sum gives the same float with or without FMA.
vec3 rtLatticePoint(uint x, uint y, uint z) {
    precise vec3 p = vec3(latticeOriginX, latticeOriginY, latticeOriginZ) + vec3(float(x), float(y), float(z)) * latticeStep;
    return p;
}

// Triangle `tri`'s vertices from the structure's buffer: float (`triangles`) or packed
// (`packedTriangles`, kernels/gpu_layout.h) when vertexBits != 0.
void rtStoredVertices(uint tri, RT_OUT(vec3) v0, RT_OUT(vec3) v1, RT_OUT(vec3) v2) {
    if (vertexBits == 0u) {
        Triangle stored = triangles[tri];  // one read of the triangle (the cache trace sees one)
        v0 = vec3(stored.v0);
        v1 = vec3(stored.v1);
        v2 = vec3(stored.v2);
        return;
    }
    const uint w = kPackedTriangleWords * tri;
    const uint a = packedTriangles[w], b = packedTriangles[w + 1u], c = packedTriangles[w + 2u];
    const uint d = packedTriangles[w + 3u], e = packedTriangles[w + 4u];
    v0 = rtLatticePoint(a & 0xFFFFu, a >> 16u, b & 0xFFFFu);
    v1 = rtLatticePoint(b >> 16u, c & 0xFFFFu, c >> 16u);
    v2 = rtLatticePoint(d & 0xFFFFu, d >> 16u, e);
}

// The configured test against the structure's triangle `tri`: updates (t, u, v) when it is hit
// in [tMin, t).
bool rtIntersectStored(RtTriangleRay r, uint tri, RT_INOUT(float) t, RT_INOUT(float) u, RT_INOUT(float) v) {
    vec3 v0, v1, v2;
    rtStoredVertices(tri, v0, v1, v2);
    return rtIntersect(r, v0, v1, v2, t, u, v);
}

// The query's one hook (pbrt's Intersect and IntersectP, bvh v2's IsAnyHit): true when a walk
// holding the hit `primitive` has answered its query and ends there: an any-hit query's first
// hit. A closest-hit walk ends by its own rule (no nearer hit can follow). Every traversal loop,
// branching and multipass, asks it after each triangle test.
bool rtQueryDone(uint primitive) { return query == kQueryAny && primitive != kNoHit; }

// Tests triangle `tri` and keeps it when it is hit nearer; true when that answers the query.
bool rtTestTriangle(RtTriangleRay r, uint tri, RT_INOUT(RtNearest) n) {
    if (rtIntersectStored(r, tri, n.t, n.u, n.v)) n.primitive = tri;
    return rtQueryDone(n.primitive);
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
    uint stackEntries;   // node-stack entries pushed or popped in memory (BVH)
    uint sink;           // xor of discarded reads: keeps the compiler from removing them
};

MpEvents mpNoEvents() {
    MpEvents e;
    e.structureReads = 0u;
    e.triangleReads = 0u;
    e.visited = 0u;
    e.tested = 0u;
    e.steps = 0u;
    e.stackEntries = 0u;
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
uint mpDoneState(RayHitState hit) { return hit.primitive != kNoHit ? kStateDoneHit : kStateLeftStructure; }

// The read an unrolled intersect iteration makes for a ray already done, on hardware that cannot
// skip it (Purcell §4.2): a list entry and the vertices of triangle `tri`, read, then discarded.
void mpDiscardTriangleRead(uint tri, RT_INOUT(MpEvents) e) {
    e.triangleReads += 1u;
    vec3 v0, v1, v2;
    rtStoredVertices(tri, v0, v1, v2);
    e.sink ^= tri ^ floatBitsToUint(v0.x) ^ floatBitsToUint(v1.y) ^ floatBitsToUint(v2.z);
}

#endif  // RT_TRAVERSAL_COMMON_GLSL
