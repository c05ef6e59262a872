#include "multipass_schedule.h"

#include <algorithm>

#include "structures/error.h"

namespace rtbench {

const char* passKindName(PassKind kind) {
    switch (kind) {
        case PassKind::Setup: return "setup";
        case PassKind::Traverse: return "traverse";
        case PassKind::Intersect: return "intersect";
        case PassKind::Write: return "write";
    }
    return "?";
}

PassKind PassScheduler::next(std::uint64_t traversing, std::uint64_t waiting) {
    if (traversing + waiting == 0) return PassKind::Write;
    if (waiting == 0) return naivePhase_ = PassKind::Traverse;
    if (traversing == 0) return naivePhase_ = PassKind::Intersect;
    if (options_.scheduling == "naive") return naivePhase_;  // stay in the phase until it drains
    const double waitingFraction = double(waiting) / double(traversing + waiting);
    return waitingFraction >= options_.oracleThreshold ? PassKind::Intersect : PassKind::Traverse;
}

MultipassCounts& MultipassCounts::operator+=(const MultipassCounts& batch) {
    for (int k = 0; k < kPassKinds; ++k) passes[std::size_t(k)] += batch.passes[std::size_t(k)];
    usefulTraverse += batch.usefulTraverse, usefulIntersect += batch.usefulIntersect;
    stencilWrites += batch.stencilWrites, structureReads += batch.structureReads, triangleReads += batch.triangleReads;
    sequence.insert(sequence.end(), batch.sequence.begin(), batch.sequence.end());
    streamSlots += batch.streamSlots;
    return *this;
}

MultipassCounts runPassLoop(const MultipassOptions& options, std::uint64_t cap, std::uint64_t rays,
                            const std::function<PassSums(PassKind)>& pass) {
    MultipassCounts counts;
    auto run = [&](PassKind kind) {
        const PassSums sums = pass(kind);
        ++counts.passes[static_cast<int>(kind)];
        if (kind == PassKind::Traverse || kind == PassKind::Intersect) counts.streamSlots += rays;
        counts.sequence.push_back(kind);
        if (kind == PassKind::Traverse) counts.usefulTraverse += sums.useful;
        if (kind == PassKind::Intersect) counts.usefulIntersect += sums.useful;
        counts.stencilWrites += sums.stencilWrites;
        counts.structureReads += sums.structureReads;
        counts.triangleReads += sums.triangleReads;
        return sums;
    };
    PassSums sums = run(PassKind::Setup);
    std::uint64_t traversing = sums.traversing, waiting = sums.waiting;
    PassScheduler scheduler(options);
    for (PassKind kind = scheduler.next(traversing, waiting); kind != PassKind::Write;
         kind = scheduler.next(traversing, waiting)) {
        if (counts.totalPasses() >= cap)
            throw Error("multipass: pass cap of " + std::to_string(cap) + " reached with " +
                        std::to_string(traversing + waiting) + " rays still active");
        sums = run(kind);
        // A pass counts only the rays it served; the others keep their state.
        if (kind == PassKind::Traverse)
            traversing = sums.traversing, waiting += sums.waiting;
        else
            waiting = sums.waiting, traversing += sums.traversing;
    }
    run(PassKind::Write);
    return counts;
}

std::uint64_t multipassPassCap(std::uint64_t maxCellsPerRay, std::uint64_t maxTrianglesPerCell,
                               const MultipassOptions& options) {
    const std::uint64_t vmax = maxCellsPerRay, lmax = std::max<std::uint64_t>(maxTrianglesPerCell, 1);
    const std::uint64_t k = options.traverseStepsPerPass, m = options.intersectionsPerPass;
    return 4 * ((vmax + k - 1) / k + (vmax * lmax + m - 1) / m) + 16;
}

}  // namespace rtbench
