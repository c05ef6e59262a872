// What every structure's multipass per-ray work reports (MpEvents), and the hit record the write
// pass makes from the hit state: ONE source for kernels/multipass_*.comp and the CPU simulator
// (methods/multipass/multipass_simulator.h), included before the structure's multipass steps.
#ifndef RT_MULTIPASS_EVENTS_GLSL
#define RT_MULTIPASS_EVENTS_GLSL

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
    HitRecord h;
    bool found = hit.primitive != kNoHit;
    h.t = found ? hit.t : kNoHitT;
    h.primitive = hit.primitive;
    h.u = found ? hit.u : 0.0f;
    h.v = found ? hit.v : 0.0f;
    h.cellsVisited = counters.cellsVisited;
    h.trianglesTested = counters.trianglesTested;
    h.traversalSteps = counters.traversalSteps;
    h.pad = 0u;
    return h;
}

#endif  // RT_MULTIPASS_EVENTS_GLSL
