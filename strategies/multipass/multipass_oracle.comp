// The oracle on the device (strategy.control = "device"): one invocation after every pass reads
// the lengths of the ray lists that pass left, logs it, and chooses the next pass by the same
// decision as the host's (multipass_oracle.glsl), writing the workgroup counts the next traverse
// and intersect dispatches read (the one not chosen gets none). No host round trip per pass:
// Christen 2005 §7's "multipassing ... directly on hardware".
#version 450
#extension GL_GOOGLE_include_directive : require
#include "multipass_common.glsl"
#include "multipass_oracle.glsl"

layout(constant_id = kSpecOracleThreshold) const uint oracleThresholdQ31 = 0u;
layout(constant_id = kSpecNaive) const uint naiveSchedule = 0u;
layout(constant_id = kSpecPassCap) const uint passCap = 0xFFFFFFFFu;
layout(constant_id = kSpecMaxGroupsX) const uint maxGroupsX = 65535u;
layout(constant_id = kSpecOracleAllRays) const uint oracleAllRays = 0u;

// Workgroups for `rays` invocations: one row when they fit maxGroupsX, else the fewest rows of
// the fewest groups (device/vulkan_context.h workgroupGrid).
uvec4 mpGroupsFor(uint rays) {
    uint groups = (rays + gl_WorkGroupSize.x - 1u) / gl_WorkGroupSize.x;
    uint y = max((groups + maxGroupsX - 1u) / maxGroupsX, 1u);
    return uvec4((groups + y - 1u) / y, y, 1u, 0u);
}

// The rays on list l: its partitions' lengths.
uint mpListLength(uint l) {
    uint n = 0u;
    for (uint p = 0u; p < listPartitions; ++p) n += MP_LIST_LENGTH(l, p);
    return n;
}

void mpClearList(uint l) {
    for (uint p = 0u; p < listPartitions; ++p) MP_LIST_LENGTH(l, p) = 0u;
}

void main() {
    if (gl_GlobalInvocationID.x != 0u || gl_GlobalInvocationID.y != 0u) return;
    if (control.status.y != 0u) return;  // the loop has ended: iterations recorded after it do nothing
    uint last = control.current.z;
    uint passes = control.current.w + 1u;  // the last pass included
    uint t = control.current.x, w = control.current.y;
    uint dispatched = last == kPassTraverse ? mpListLength(t) : last == kPassIntersect ? mpListLength(2u + w) : rtRayCount();
    // The last pass read its state's current list and filled the other one of the pair.
    if (last == kPassTraverse) {
        mpClearList(t);
        t = 1u - t;
    } else if (last == kPassIntersect) {
        mpClearList(2u + w);
        w = 1u - w;
    }
    uint traversing = mpListLength(t), waiting = mpListLength(2u + w);
    PassLogEntry entry;
    for (uint i = 0u; i < kPassLogSums; ++i) {
        entry.sums[i] = passCounters.counts[i];
        passCounters.counts[i] = uint64_t(0);
    }
    entry.kindLists = uvec4(last, traversing, waiting, dispatched);
    passLog[(passes - 1u) % kPassLogEntries] = entry;  // a ring: the host reads it after every submission

    uint phase = max(control.status.x, kPassTraverse);  // all zeros: the naive schedule starts traversing
    uint next = mpNextPass(traversing, waiting, phase, oracleThresholdQ31, naiveSchedule != 0u,
                           oracleAllRays != 0u ? rtRayCount() : 0u);
    bool capped = next != kPassWrite && passes >= passCap;  // as runPassLoop: the cap counts setup
    bool overflow = traversing > rtRayCount() || waiting > rtRayCount();  // a list holds more rays than the stream: a bug
    bool ended = next == kPassWrite || capped || overflow;
    control.status = uvec4(phase, ended ? 1u : 0u, capped ? 1u : 0u, overflow ? 1u : 0u);
    control.traverseGroups = !ended && next == kPassTraverse ? mpGroupsFor(traversing) : uvec4(0u);
    control.intersectGroups = !ended && next == kPassIntersect ? mpGroupsFor(waiting) : uvec4(0u);
    control.current = uvec4(t, w, ended ? kPassWrite : next, passes);
}
