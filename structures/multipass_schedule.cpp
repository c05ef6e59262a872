#include "multipass_schedule.h"

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

std::uint64_t multipassPassCap(const unsigned resolution[3], std::uint32_t maxReferencesInCell,
                               const MultipassOptions& options) {
    const std::uint64_t vmax = std::uint64_t(resolution[0]) + resolution[1] + resolution[2];
    const std::uint64_t k = options.traverseStepsPerPass, m = options.intersectionsPerPass;
    const std::uint64_t perRay = (vmax + k - 1) / k + (vmax * std::max<std::uint64_t>(maxReferencesInCell, 1) + m - 1) / m;
    return 4 * perRay + 16;
}

}  // namespace rtbench
