#include "multipass_schedule.h"

#include <algorithm>
#include <cmath>

#include "kernels/gpu_layout.h"

#include "core/error.h"

namespace rtbench {

namespace oracle {
using namespace gpu;
using std::uint64_t;
#define RT_INOUT(T) T&
#include "multipass_oracle.glsl"
#undef RT_INOUT
}  // namespace oracle

const char* passKindName(PassKind kind) {
    switch (kind) {
        case PassKind::Setup: return "setup";
        case PassKind::Traverse: return "traverse";
        case PassKind::Intersect: return "intersect";
        case PassKind::Write: return "write";
    }
    return "?";
}

std::uint32_t oracleThresholdQ31(double threshold) {
    if (!(threshold >= 0.0 && threshold <= 1.0))
        throw Error("multipass: oracle_threshold " + std::to_string(threshold) + " is outside [0, 1]");
    return std::uint32_t(std::floor(std::ldexp(threshold, 31)));
}

PassKind PassScheduler::next(std::uint64_t traversing, std::uint64_t waiting) {
    if (traversing + waiting > 0xFFFFFFFFull)
        throw Error("multipass: " + std::to_string(traversing + waiting) +
                    " active rays in one stream, over the oracle's 2^32 - 1 (strategy.batch_rays splits the stream)");
    std::uint32_t phase = static_cast<std::uint32_t>(naivePhase_);
    const std::uint32_t kind =
        oracle::mpNextPass(std::uint32_t(traversing), std::uint32_t(waiting), phase, thresholdQ31_, naive_, basisRays_);
    naivePhase_ = static_cast<PassKind>(phase);
    return static_cast<PassKind>(kind);
}

MultipassCounts& MultipassCounts::operator+=(const MultipassCounts& batch) {
    for (int k = 0; k < kPassKinds; ++k) passes[std::size_t(k)] += batch.passes[std::size_t(k)];
    usefulTraverse += batch.usefulTraverse, usefulIntersect += batch.usefulIntersect;
    stencilWrites += batch.stencilWrites, structureReads += batch.structureReads, triangleReads += batch.triangleReads;
    stackEntries += batch.stackEntries;
    sequence.insert(sequence.end(), batch.sequence.begin(), batch.sequence.end());
    streamSlots += batch.streamSlots;
    wholeStreamSlots += batch.wholeStreamSlots;
    listAppends += batch.listAppends;
    return *this;
}

MultipassCounts runPassLoop(const MultipassOptions& options, std::uint64_t cap, std::uint64_t rays,
                            const std::function<PassSums(PassKind)>& pass,
                            const std::function<void(std::uint64_t, std::uint64_t)>& afterPass) {
    MultipassCounts counts;
    std::uint64_t traversing = 0, waiting = 0;  // active rays in each state
    auto run = [&](PassKind kind) {
        const PassSums sums = pass(kind);
        ++counts.passes[static_cast<int>(kind)];
        if (kind == PassKind::Traverse || kind == PassKind::Intersect) {
            counts.streamSlots += !options.deviceControl ? rays : kind == PassKind::Traverse ? traversing : waiting;
            counts.wholeStreamSlots += rays;
        }
        counts.listAppends += sums.traversing + sums.waiting;
        counts.sequence.push_back(kind);
        if (kind == PassKind::Traverse) counts.usefulTraverse += sums.useful;
        if (kind == PassKind::Intersect) counts.usefulIntersect += sums.useful;
        counts.stencilWrites += sums.stencilWrites;
        counts.structureReads += sums.structureReads;
        counts.triangleReads += sums.triangleReads;
        counts.stackEntries += sums.stackEntries;
        return sums;
    };
    PassSums sums = run(PassKind::Setup);
    traversing = sums.traversing, waiting = sums.waiting;
    if (afterPass) afterPass(traversing, waiting);
    PassScheduler scheduler(options, rays);
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
        if (afterPass) afterPass(traversing, waiting);
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
