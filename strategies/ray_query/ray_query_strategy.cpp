#include "ray_query_strategy.h"

#include <algorithm>

#include "device/embedded_kernels.h"
#include "structures/driver/driver_structure.h"
#include "strategies/branching/branching_strategy.h"
#include "strategies/dispatch_timer.h"
#include "strategies/stream_batches.h"
#include "core/error.h"

namespace rtbench {

std::string rayQueryRefusal(const DeviceInfo& device) {
    if (device.rayQuery) return "";
    return "device lacks VK_KHR_ray_query: " + device.name + " (" + device.driver + ") has no " + device.rayQueryMissing +
           " (lavapipe gained the driver's ray tracing in Mesa 24.1)";
}

ImpossibleHits impossibleHits(const std::vector<gpu::Ray>& rays, const std::vector<gpu::HitRecord>& hits) {
    ImpossibleHits found;
    for (std::size_t i = 0; i < hits.size(); ++i) {
        const gpu::HitRecord& h = hits[i];
        const bool possible = h.primitive == gpu::kNoHit
                                  ? h.t == gpu::kNoHitT
                                  : h.t >= rays[i].originTMin.w && h.t < rays[i].directionTMax.w;
        if (!possible && found.rays++ == 0) found.first = i;
    }
    return found;
}

void judgeByTheExactReference(const std::vector<gpu::Ray>& rays, StrategyRun& run, const std::string& who) {
    // What can be checked of another's arithmetic: every answer lies in its ray's interval, on a
    // triangle of the scene (the runner), and the same rays get the same answers (the timer).
    // Accuracy is the exact reference's to judge, as Embree's is.
    const ImpossibleHits impossible = impossibleHits(rays, run.hits);
    if (impossible.rays)
        throw Error(who + " answered " + std::to_string(impossible.rays) + " of " + std::to_string(rays.size()) +
                    " rays outside their interval [tMin, tMax) (first: ray " + std::to_string(impossible.first) + ", t " +
                    std::to_string(run.hits[impossible.first].t) + ")");
    run.metrics.work.hits = std::uint64_t(std::count_if(run.hits.begin(), run.hits.end(),
                                                        [](const gpu::HitRecord& h) { return h.primitive != gpu::kNoHit; }));
    run.metrics.countsKnown = false;
    run.cpuCompared = false;
    run.countsCompared = false;
}

namespace {

// One dispatch's rays on the device: their buffers, the kernel and its descriptor set.
class RayQueryDispatch {
public:
    RayQueryDispatch(VulkanContext& vk, const std::vector<gpu::Ray>& rays, std::uint32_t query, VkDeviceAddress topLevel,
                     unsigned workgroupSize)
        : vk_(vk), count_(rays.size()) {
        try {
            create(rays, query, topLevel, workgroupSize);
        } catch (...) {
            release();  // what a failed setup made so far
            throw;
        }
    }
    ~RayQueryDispatch() { release(); }
    RayQueryDispatch(const RayQueryDispatch&) = delete;
    RayQueryDispatch& operator=(const RayQueryDispatch&) = delete;

    VulkanContext::DispatchCall call() const { return {&pipeline_, set_, &params_, count_}; }
    std::vector<gpu::HitRecord> hits() const {
        std::vector<gpu::HitRecord> h(count_);
        vk_.download(hits_, h.data(), h.size() * sizeof(gpu::HitRecord));
        return h;
    }

private:
    void create(const std::vector<gpu::Ray>& rays, std::uint32_t query, VkDeviceAddress topLevel, unsigned workgroupSize) {
        VulkanContext& vk = vk_;
        rays_ = vk.createStorageBuffer(rays.size() * sizeof(gpu::Ray), "ray (" + std::to_string(rays.size()) + " rays)");
        vk.upload(rays_, rays.data(), rays.size() * sizeof(gpu::Ray));
        hits_ = vk.createStorageBuffer(rays.size() * sizeof(gpu::HitRecord), "hit record (" + std::to_string(rays.size()) + " rays)");
        params_.stream = {std::uint32_t(rays.size()), query, 0u, 0u};
        params_.topLevel = topLevel;
        pipeline_ = vk.createComputePipeline(embeddedKernel("ray_query"), 2, sizeof(gpu::RayQueryParams), workgroupSize,
                                             {{gpu::kSpecWorkgroupSize, workgroupSize}});
        set_ = vk.createDescriptorSet(pipeline_, {&rays_, &hits_});
    }
    void release() {
        if (set_) vk_.destroy(set_);
        set_ = VK_NULL_HANDLE;
        vk_.destroy(pipeline_);
        vk_.destroy(hits_);
        vk_.destroy(rays_);
    }

    VulkanContext& vk_;
    std::uint64_t count_;
    Buffer rays_, hits_;
    gpu::RayQueryParams params_{};
    ComputePipeline pipeline_{};
    VkDescriptorSet set_ = VK_NULL_HANDLE;
};

StrategyRun runRayQuery(VulkanContext& vk, const Structure& structure, const RayBatch& batch, const RunConfig&,
                        const TimingOptions& timing, Row& row) {
    if (const std::string why = rayQueryRefusal(vk.info()); !why.empty()) throw Error(why);
    const auto* driver = dynamic_cast<const DriverStructure*>(&structure);
    if (!driver) throw Error("strategy.type = ray_query traces the driver's acceleration structure: structure.type must be driver");
    const VkDeviceAddress topLevel = driver->accelerationStructure().topLevelAddress();
    const std::vector<gpu::Ray>& rays = batch.rays;

    // Batches of what one binding holds of the ray or hit records, one dispatch each.
    struct BatchRun {
        std::vector<gpu::HitRecord> hits;
        std::unique_ptr<KernelTimer> timer;
    };
    StrategyRun run;
    std::size_t batches = 0;
    run.timer = traceInBatches(
        rays, raysPerBinding(vk.info(), sizeof(gpu::HitRecord), timing.workgroupSize),
        [&](const std::vector<gpu::Ray>& part) {
            auto dispatch = std::make_unique<RayQueryDispatch>(vk, part, batch.query, topLevel, timing.workgroupSize);
            vk.dispatchAll({dispatch->call()});
            BatchRun b{dispatch->hits(), nullptr};
            b.timer = std::make_unique<DispatchTimer<RayQueryDispatch>>(vk, std::move(dispatch), b.hits, "ray_query kernel");
            return b;
        },
        [&](const BatchRun& b) {
            run.hits.insert(run.hits.end(), b.hits.begin(), b.hits.end());
            ++batches;
        });
    put(row, wholeTraversalColumns().streamBatches, batches);

    judgeByTheExactReference(rays, run, "the driver's ray query");
    return run;
}

}  // namespace

const StrategyType& rayQueryStrategyType() {
    static const StrategyType type = [] {
        StrategyType t;
        t.name = "ray_query";
        t.help = "the driver's own traversal (VK_KHR_ray_query) of its own acceleration structure (structure.type = driver); "
                 "judged against the exact reference, no work counted";
        t.onlyStructure = "driver";
        t.columns = {wholeTraversalColumns().streamBatches.spec()};
        t.refusal = rayQueryRefusal;
        t.trace = runRayQuery;
        return t;
    }();
    return type;
}

}  // namespace rtbench
