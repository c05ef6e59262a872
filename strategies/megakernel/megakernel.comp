// A megakernel with fine-grained scheduling (Parker et al. 2013, OptiX, §5.1-5.2): one invocation
// per ray runs the structure's multipass state machine (mpSetup, then mpTraverse or mpIntersect,
// one traversal step or one triangle test at a time) in one loop, the ray's state in registers.
// At each iteration the subgroup chooses which state it runs (`schedule`): all of those present,
// serialised as SIMT hardware runs a divergent switch (§5.1), or one for the whole subgroup by a
// fixed priority or by majority, the lanes in the other state idling (§5.2). The loop runs while
// any lane of the subgroup is active, so its iterations and choices are the subgroup's own.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "bindings.glsl"
#include "megakernel_layout.h"
#include "traversal_common.glsl"
#define MP_PRIVATE_STACK  // a structure's stack in an array of its own (structures/bvh/bvh_traversal.glsl)
#include "structure.glsl"

layout(constant_id = kSpecSchedule) const uint schedule = kScheduleIntersectFirst;

// One subgroup execution of a state by `lanes` of its lanes (instrumented runs).
void mkCountRun(uint slot, uint lanes) {
    if (instrument != 0u && subgroupElect()) {
        atomicAdd(passCounters.counts[slot], 1ul);
        atomicAdd(passCounters.counts[kCountActiveLanes], uint64_t(lanes));
        atomicAdd(passCounters.counts[kCountLaneSlots], uint64_t(gl_SubgroupSize));
    }
}

void mkAdd(RT_INOUT(RayCounters) c, MpEvents e) {
    c.cellsVisited += e.visited;
    c.trianglesTested += e.tested;
    c.traversalSteps += e.steps;
}

void main() {
    uint rayIndex = rtRayIndex();
    bool live = rayIndex < rtRayCount();
    Ray ray;
    RtTraversalState ts;
    RayHitState hit;
    RayCounters c = RayCounters(0u, 0u, 0u, 0u);
    uint state = kStateLeftStructure;  // lanes past the stream: done from the start
    if (live) {
        ray = rays[rayIndex];
        MpEvents e = mpNoEvents();
        state = mpSetup(ray, ts, hit, e);
        mkAdd(c, e);
    }
    while (subgroupBallotBitCount(subgroupBallot(state == kStateTraversing || state == kStateWaiting)) > 0u) {
        // Each lane's state at the start of the iteration: a lane runs at most one step in it.
        bool traversing = state == kStateTraversing, waiting = state == kStateWaiting;
        uint nTraverse = subgroupBallotBitCount(subgroupBallot(traversing));
        uint nIntersect = subgroupBallotBitCount(subgroupBallot(waiting));
        bool runTraverse, runIntersect;
        if (schedule == kScheduleSwitch) {
            runTraverse = nTraverse > 0u;
            runIntersect = nIntersect > 0u;
        } else if (schedule == kScheduleTraverseFirst) {
            runTraverse = nTraverse > 0u;
            runIntersect = !runTraverse;
        } else if (schedule == kScheduleMajority) {
            runIntersect = nIntersect >= nTraverse;
            runTraverse = !runIntersect;
        } else {  // kScheduleIntersectFirst
            runIntersect = nIntersect > 0u;
            runTraverse = !runIntersect;
        }
        if (runTraverse) {
            if (traversing) {
                MpEvents e = mpNoEvents();
                state = mpTraverse(ray, ts, hit, e);
                mkAdd(c, e);
            }
            mkCountRun(kCountRunsTraverse, nTraverse);
        }
        if (runIntersect) {
            if (waiting) {
                MpEvents e = mpNoEvents();
                state = mpIntersect(ray, ts, hit, e);
                mkAdd(c, e);
            }
            mkCountRun(kCountRunsIntersect, nIntersect);
        }
    }
    if (!live) return;
    rtWriteRecord(rayIndex, mpHitRecord(hit, c));
}
