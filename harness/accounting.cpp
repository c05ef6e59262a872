#include "accounting.h"

#include <algorithm>

namespace rtbench {

ArchitectureMetrics branchingMetrics(const std::vector<gpu::HitRecord>& hits, std::uint64_t activeLanes,
                                     std::uint64_t laneSlots) {
    ArchitectureMetrics m;
    m.work = workStats(hits);
    m.passes = 1;
    m.simdEfficiency = laneSlots ? double(activeLanes) / double(laneSlots) : 0.0;
    const std::uint64_t rays = hits.size();
    m.bytes.state = rays * bytes::kBranchingState;
    m.bytes.voxel = m.work.voxelsTotal * 2 * bytes::kCellOffset;
    m.bytes.triangleList = m.work.trianglesTotal * bytes::kListEntry;
    m.bytes.vertices = m.work.trianglesTotal * bytes::kTriangle;
    m.bytes.output = rays * bytes::kOutput;
    return m;
}

ArchitectureMetrics multipassMetrics(const std::vector<gpu::HitRecord>& hits, const MultipassCounts& counts,
                                     const MultipassOptions& options) {
    ArchitectureMetrics m;
    m.work = workStats(hits);
    const std::uint64_t rays = hits.size();
    m.passes = counts.totalPasses();
    m.passesSetup = counts.passes[static_cast<int>(PassKind::Setup)];
    m.passesTraverse = counts.passes[static_cast<int>(PassKind::Traverse)];
    m.passesIntersect = counts.passes[static_cast<int>(PassKind::Intersect)];
    m.passesWrite = counts.passes[static_cast<int>(PassKind::Write)];
    // Purcell: max steps / K + max tests / M, each rounded up.
    const std::uint64_t k = options.traverseStepsPerPass, mm = options.intersectionsPerPass;
    m.passesLowerBound = (m.work.stepsPerRayMax + k - 1) / k + (m.work.trianglesPerRayMax + mm - 1) / mm;
    const std::uint64_t loopPasses = m.passesTraverse + m.passesIntersect;
    m.simdEfficiency = loopPasses ? double(counts.usefulTraverse + counts.usefulIntersect) / double(loopPasses * rays) : 1.0;
    // Every traverse and intersect pass reads every ray's stencil byte; changes are written.
    m.bytes.stencil = loopPasses * rays * bytes::kStencil + counts.stencilWrites * bytes::kStencil;
    m.bytes.voxel = counts.offsetReads * bytes::kCellOffset;
    m.bytes.triangleList = counts.triangleReads * bytes::kListEntry;
    m.bytes.vertices = counts.triangleReads * bytes::kTriangle;
    m.bytes.output = rays * bytes::kOutput;
    m.bytes.state = rays * bytes::kSetupState + counts.usefulTraverse * bytes::kTraverseState +
                    counts.usefulIntersect * bytes::kIntersectState + rays * bytes::kWriteState;
    return m;
}

}  // namespace rtbench
