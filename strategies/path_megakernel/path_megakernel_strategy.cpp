#include "path_megakernel_strategy.h"

#include <cstring>

#include "path_megakernel_layout.h"
#include "strategies/branching/branching_strategy.h"
#include "methods/metrics.h"
#include "strategies/whole_path.h"
#include "core/error.h"
#include "schema/column.h"

namespace rtbench {

namespace {

constexpr std::uint32_t kMadeInfo = gpu::kBindingPathMadeInfo - gpu::kBindingStrategy;
constexpr std::uint32_t kMade = gpu::kBindingPathMade - gpu::kBindingStrategy;

// What the kernel left at each path: its batch ray and record, and whether it reached the batch.
struct PathEnds {
    std::vector<gpu::Ray> rays;
    std::vector<gpu::HitRecord> hits;
    std::vector<std::uint32_t> made, weightBits;
};

PathEnds downloadPathEnds(GpuBuffers& buffers, std::uint64_t paths) {
    PathEnds e;
    e.hits = buffers.downloadHits();
    e.hits.resize(paths);
    const std::vector<std::uint8_t> rays = buffers.downloadStrategyBuffer(kMade);
    const std::vector<std::uint8_t> info = buffers.downloadStrategyBuffer(kMadeInfo);
    e.rays.resize(paths);
    std::memcpy(e.rays.data(), rays.data(), paths * sizeof(gpu::Ray));
    for (std::uint64_t p = 0; p < paths; ++p) {
        std::uint32_t entry[4];
        std::memcpy(entry, info.data() + 16 * p, 16);
        e.made.push_back(entry[0]);
        e.weightBits.push_back(entry[3]);
    }
    return e;
}

// The batch as the kernel left it, in the batch's order (its rays come in the order of their
// paths), and how it differs from the CPU's batch ("" when it does not): the paths that reached
// it, each ray's bits and weight.
std::string batchMismatch(const PathEnds& e, const PathGeneration& cpu, std::vector<gpu::HitRecord>& hits) {
    std::uint64_t reached = 0;
    for (std::uint32_t m : e.made) reached += m != 0;
    hits.assign(cpu.rays->size(), gpu::HitRecord{});
    std::uint64_t differing = 0;
    std::string first;
    for (std::size_t b = 0; b < cpu.rays->size(); ++b) {
        const std::uint32_t p = cpu.paths ? (*cpu.paths)[b] : std::uint32_t(b);
        const float weight = cpu.weights ? (*cpu.weights)[b] : 1.0f;
        std::uint32_t weightBits;
        std::memcpy(&weightBits, &weight, 4);
        const char* what = p >= e.made.size() || !e.made[p]                               ? "path that never reached the batch"
                           : std::memcmp(&e.rays[p], &(*cpu.rays)[b], sizeof(gpu::Ray)) ? "ray"
                           : e.weightBits[p] != weightBits                              ? "weight"
                                                                                         : nullptr;
        if (p < e.hits.size()) hits[b] = e.hits[p];
        if (what && differing++ == 0) first = "ray " + std::to_string(b) + "'s " + what;
    }
    if (reached != cpu.rays->size())
        return "batch: " + std::to_string(reached) + " paths reached it on the device, " + std::to_string(cpu.rays->size()) +
               " on the CPU";
    if (!differing) return "";
    return "batch (" + std::to_string(differing) + " of " + std::to_string(cpu.rays->size()) + " rays; first: " + first + ")";
}

class PathMegakernelTimer : public KernelTimer {
public:
    PathMegakernelTimer(VulkanContext& vk, std::unique_ptr<GpuBuffers> buffers, ComputePipeline timed,
                        std::uint64_t cameraRays, std::uint64_t paths, PathEnds counted)
        : vk_(vk), buffers_(std::move(buffers)), timed_(timed), cameraRays_(cameraRays), paths_(paths),
          counted_(std::move(counted)) {}
    ~PathMegakernelTimer() override { vk_.destroy(timed_); }
    TimedBatch time(int warmups, int repetitions) override {
        const std::vector<VulkanContext::DispatchCall> calls(
            std::size_t(warmups + repetitions),
            {&timed_, buffers_->descriptorSet(timed_), buffers_->pushConstants(), cameraRays_});
        return splitWarmups(vk_.dispatchAll(calls), warmups);
    }
    // The paths that reached the batch, then their records: a path that stopped short in the
    // timed run would keep the instrumented run's record.
    void checkHits() override {
        const PathEnds e = downloadPathEnds(*buffers_, paths_);
        for (std::uint64_t p = 0; p < paths_; ++p)
            if ((e.made[p] != 0) != (counted_.made[p] != 0))
                throw Error("path megakernel: path " + std::to_string(p) + " reached the batch in the " +
                            (e.made[p] ? "timed run but not in the instrumented one" : "instrumented run but not in the timed one") +
                            ": the kernel gives different results on the same input");
        expectSameHits(e.hits, counted_.hits, "path megakernel");
    }

private:
    VulkanContext& vk_;
    std::unique_ptr<GpuBuffers> buffers_;
    ComputePipeline timed_;
    std::uint64_t cameraRays_, paths_;
    PathEnds counted_;  // the instrumented run's, by path
};

// Rays the path megakernel traced, counted on the device (results schema 19).
const Column<std::uint64_t>& raysTracedColumn() {
    static const Column<std::uint64_t> column({"path_megakernel_rays_traced", ColumnKind::Exact, "rays",
                                               "path_megakernel: rays the kernel traced, counted on the device (must equal "
                                               "whole_path_rays)", 0.0, false, {}, 19});
    return column;
}

StrategyRun runPathMegakernelStrategy(VulkanContext& vk, const Structure& structure, const RayBatch& batch,
                                      const BatchPath& path, const RunConfig&, const TimingOptions& timing, Row& row) {
    requireTraceablePath(path, "path_megakernel");
    for (std::size_t g = 1; g < path.passes.size(); ++g)
        if (path.passes[g].pass.z != 1)
            throw Error("strategy.type = path_megakernel follows one ray per hit after the first pass, and pass " +
                        std::to_string(g + 1) + " makes " + std::to_string(path.passes[g].pass.z));
    requireWholeSubgroups(vk, timing.workgroupSize);
    const std::uint64_t cameraRays = path.generations.front().rays->size();
    const std::uint64_t paths = wholePathCapacity(path).queue;  // fan-out 1 after the first pass
    auto buffers = uploadWholePath(vk, structure, path, paths, {0, 0, paths}, 0, std::uint32_t(paths));
    const std::string kernel = structure.kernelPrefix() + "_path_megakernel";
    KernelSpec spec = structureKernelSpec(structure, timing.workgroupSize, batch.query, {});
    ComputePipeline counted = buffers->createKernel(kernel, spec);
    vk.dispatch(counted, buffers->descriptorSet(counted), buffers->pushConstants(), cameraRays, buffers->passCounters());
    vk.destroy(counted);
    const gpu::PassCounters counters = buffers->readPassCounters();
    const PathEnds ends = downloadPathEnds(*buffers, paths);
    writeWholePathColumns(path, row);
    const std::uint64_t traced = counters.counts[gpu::kCountPathRaysTraced];
    put(row, raysTracedColumn(), traced);

    // Judged as a whole-traversal kernel's run: its batch records, in the batch's order, and its
    // ballots against the lane model of its own schedule.
    BranchingRun batchRun;
    const std::string mismatch = batchMismatch(ends, path.generations.back(), batchRun.hits);
    batchRun.activeLanes = counters.counts[gpu::kCountActiveLanes];
    batchRun.laneSlots = counters.counts[gpu::kCountLaneSlots];
    spec.instrument = false;
    const ComputePipeline timed = buffers->createKernel(kernel, spec);
    batchRun.timer = std::make_unique<PathMegakernelTimer>(vk, std::move(buffers), timed, cameraRays, paths, ends);
    const LaneCounts lanes = pathLaneCounts(structure, path, batch.query, vk.info().subgroupSize, loopIterationBudget(vk.info()));
    StrategyRun run = judgeWholeTraversal(vk, structure, batch, std::move(batchRun), lanes,
                                          ": a camera ray's whole path runs in one invocation (the wavefront traces a "
                                          "generation per dispatch)",
                                          row);
    if (traced != path.rays())
        run.countsMismatch = "rays traced (" + std::to_string(traced) + " on the device, " + std::to_string(path.rays()) +
                             " on the path) differ";
    if (!mismatch.empty()) run.countsMismatch = mismatch + " differs";
    return run;
}

}  // namespace

const StrategyType& pathMegakernelStrategyType() {
    static const StrategyType type = [] {
        StrategyType t;
        t.name = "path_megakernel";
        t.help = "the whole path in one kernel: each invocation traces its camera ray and every path its hit starts, shading "
                 "between the traces (Laine, Karras & Aila 2013's megakernel, the wavefront's peer)";
        // The camera rays' copy, a batch ray and its flags (one path per camera ray).
        t.ownBytesPerRay = sizeof(gpu::Ray) + sizeof(gpu::Ray) + 16;
        t.columns = wholePathStrategyColumns({raysTracedColumn().spec()});
        t.trace = runPathMegakernelStrategy;
        return t;
    }();
    return type;
}

}  // namespace rtbench
