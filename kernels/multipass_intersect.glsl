// The intersect pass's loop, shared by every structure (Purcell §3.2 with M triangles per pass):
// include after the structure defines `uint mpTriangleAt(uint position)`, the triangle at a
// position of its current range (a list entry for the grid and the BVH, the index itself for
// brute force).
#ifndef RT_MULTIPASS_INTERSECT_GLSL
#define RT_MULTIPASS_INTERSECT_GLSL

// Up to intersectionsPerPass triangles at positions [position, end); once the range ends, the rest
// of the unrolled iterations read and discard the last one (unless suppressed), as non-branching
// hardware would. True when the range ended in this pass, or the query was answered (rtQueryDone).
bool mpIntersectRange(Ray ray, RT_INOUT(uint) position, uint end, RT_INOUT(RayHitState) hit, RT_INOUT(MpEvents) e) {
    RtTriangleRay r = rtTriangleRay(ray);
    bool ended = false;
    for (uint i = 0u; i < intersectionsPerPass; ++i) {
        if (!ended) {
            uint tri = mpTriangleAt(position);
            e.triangleReads += 1u;
            e.tested += 1u;
            if (rtIntersectStored(r, tri, hit.t, hit.u, hit.v)) hit.primitive = tri;
            position += 1u;
            ended = position == end || rtQueryDone(hit.primitive);
        } else if (suppressFinishedReads == 0u) {
            mpDiscardTriangleRead(mpTriangleAt(end - 1u), e);
        }
    }
    return ended;
}

#endif  // RT_MULTIPASS_INTERSECT_GLSL
