#include "accounting.h"

#include <algorithm>

namespace rtbench {

double lockStepStreamEfficiency(const WorkStats& work, std::uint64_t rays) {
    const double slots = double(rays) * double(work.workPerRayMax);
    return slots > 0 ? double(work.stepsTotal + work.trianglesTotal) / slots : 1.0;
}

ArchitectureMetrics branchingMetrics(const std::vector<gpu::HitRecord>& hits, std::uint64_t activeLanes,
                                     std::uint64_t laneSlots, const StructureCosts& costs) {
    ArchitectureMetrics m;
    m.work = workStats(hits);
    m.passes = 1;
    m.simdEfficiency = m.laneUtilisation = laneSlots ? double(activeLanes) / double(laneSlots) : 0.0;
    const std::uint64_t rays = hits.size();
    m.purcellSimdEfficiency = lockStepStreamEfficiency(m.work, rays);
    m.bytes.state = rays * bytes::kBranchingState;
    m.bytes.cells = m.work.cellsTotal * costs.bytesPerCellVisit;
    m.bytes.triangleList = m.work.trianglesTotal * costs.bytesPerListEntry;
    m.bytes.vertices = m.work.trianglesTotal * costs.bytesPerTriangle;
    m.bytes.output = rays * bytes::kOutput;
    return m;
}

ArchitectureMetrics multipassMetrics(const std::vector<gpu::HitRecord>& hits, const MultipassCounts& counts,
                                     const MultipassOptions& options, const StructureCosts& costs) {
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
    const double useful = double(counts.usefulTraverse + counts.usefulIntersect);
    m.simdEfficiency = loopPasses ? useful / double(counts.streamSlots) : 1.0;
    m.purcellSimdEfficiency = loopPasses ? useful / double(counts.wholeStreamSlots) : 1.0;
    // Every traverse and intersect pass reads the stencil byte of every ray of its stream (of its
    // batch); changes are written. With the control on the device a pass reads its compacted list
    // instead (an entry per slot) and appends each ray it leaves active to a list; the oracle
    // kernel's 80-byte control block and log entry per pass are not counted.
    m.bytes.stencil = (options.deviceControl ? 0 : counts.streamSlots * bytes::kStencil) + counts.stencilWrites * bytes::kStencil;
    if (options.deviceControl) m.bytes.compaction = (counts.streamSlots + counts.listAppends) * bytes::kListEntry;
    m.bytes.cells = counts.structureReads * costs.bytesPerStructureRead;
    m.bytes.triangleList = counts.triangleReads * costs.bytesPerListEntry;
    m.bytes.vertices = counts.triangleReads * costs.bytesPerTriangle;
    m.bytes.output = rays * bytes::kOutput;
    // The per-ray state each pass moves (Purcell's state textures): setup reads the ray and
    // writes traversal and hit state; traverse reads the ray, traversal and hit state and writes
    // the traversal state; intersect also writes the hit state; write reads the hit state. The
    // traversal state's node stack (BVH) stays in memory, its own category: the entries pushed
    // and popped.
    const std::uint64_t s = costs.traversalStateBytes - costs.stackBytes;
    const std::uint64_t setup = bytes::kRay + s + bytes::kHitState;
    const std::uint64_t traverse = bytes::kRay + s + bytes::kHitState + s;
    const std::uint64_t intersect = traverse + bytes::kHitState;
    m.bytes.state = rays * setup + counts.usefulTraverse * traverse + counts.usefulIntersect * intersect +
                    rays * bytes::kHitState;
    m.bytes.stack = counts.stackEntries * bytes::kStackEntry;
    return m;
}

}  // namespace rtbench
