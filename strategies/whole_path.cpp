#include "whole_path.h"

#include <algorithm>

#include "strategies/branching/branching_strategy.h"
#include "core/error.h"

namespace rtbench {

void requireTraceablePath(const BatchPath& path, const std::string& strategy) {
    if (!path.notUniform.empty())
        throw Error("strategy.type = " + strategy + " traces paths over one material and no light, and this ray type's " +
                    path.notUniform + " (rays.type primary, reflection, refraction, path and ao can)");
    if (path.passes.size() > gpu::kPathMaxPasses)
        throw Error("strategy.type = " + strategy + ": " + std::to_string(path.passes.size()) + " shading passes, at most " +
                    std::to_string(gpu::kPathMaxPasses));
}

WholePathCapacity wholePathCapacity(std::uint64_t cameraRays, const std::vector<std::uint32_t>& fanOuts) {
    WholePathCapacity c{cameraRays, 0};
    std::uint64_t rays = cameraRays;
    for (std::uint32_t f : fanOuts) {
        rays *= f;
        if (rays > 0xFFFFFFFFull)
            throw Error("a generation of " + std::to_string(rays) + " rays would outgrow 32-bit ray indices");
        c.slots = std::max(c.slots, rays);
        c.queue = std::max(c.queue, rays);
    }
    return c;
}

WholePathCapacity wholePathCapacity(const BatchPath& path) {
    std::vector<std::uint32_t> fanOuts;
    for (const gpu::ShadingParams& p : path.passes) fanOuts.push_back(p.pass.z);
    return wholePathCapacity(path.generations.front().rays->size(), fanOuts);
}

std::unique_ptr<GpuBuffers> uploadWholePath(VulkanContext& vk, const Structure& structure, const BatchPath& path,
                                            std::uint64_t streamRays, const WholePathSizes& sizes,
                                            std::uint32_t queueCapacity, std::uint32_t slotCapacity) {
    const std::vector<gpu::Ray>& camera = *path.generations.front().rays;
    // A slot of no entries still binds 4 bytes (GpuBuffers' rule for an empty slot).
    auto atLeast4 = [](std::uint64_t bytes) { return std::max<std::uint64_t>(bytes, 4); };
    auto buffers = std::make_unique<GpuBuffers>(
        vk, std::vector<gpu::Ray>(streamRays), structure.buffers(), structure.params(),
        std::vector<BufferSize>{
            {"the path's control block", sizeof(gpu::WholePathControl) + 4 * sizes.groupSums},
            {"the path's camera rays", atLeast4(camera.size() * sizeof(gpu::Ray))},
            {"the path's queue (parent, path, weight)", atLeast4(sizes.queue * 16)},
            {"the path's made rays", atLeast4(sizes.slots * sizeof(gpu::Ray))},
            {"the path's made flags", atLeast4(sizes.slots * 16)},
            {"the path's triangles", atLeast4(path.triangles.size() * sizeof(gpu::Triangle))}});
    gpu::WholePathControl control{};
    control.limits = gpu::uvec4(queueCapacity, slotCapacity, std::uint32_t(path.passes.size()), 0u);
    control.material = path.material;
    std::copy(path.passes.begin(), path.passes.end(), control.passes);
    buffers->uploadStrategyBuffer(gpu::kBindingPathControl - gpu::kBindingStrategy, &control, sizeof control);
    buffers->uploadStrategyBuffer(gpu::kBindingPathCamera - gpu::kBindingStrategy, camera.data(), camera.size() * sizeof(gpu::Ray));
    buffers->uploadStrategyBuffer(gpu::kBindingPathTriangles - gpu::kBindingStrategy, path.triangles.data(), path.triangles.size() * sizeof(gpu::Triangle));
    return buffers;
}

namespace {

// What every whole-path strategy writes (results schema 19).
struct WholePathColumns {
    ColumnGroup group;
    Column<std::uint64_t> generations = group.add<std::uint64_t>(
        {"whole_path_generations", ColumnKind::Exact, "generations",
         "wavefront, path_megakernel: generations traced on the device, the camera rays' and the batch's included", 0.0, false, {}, 19});
    Column<std::uint64_t> rays = group.add<std::uint64_t>(
        {"whole_path_rays", ColumnKind::Exact, "rays",
         "wavefront, path_megakernel: rays traced over those generations: what the kernel time covers, what Embree traces "
         "beside it and the rates count", 0.0, false, {}, 19});
};

const WholePathColumns& wholePathColumns() {
    static const WholePathColumns columns;
    return columns;
}

}  // namespace

std::vector<ColumnSpec> wholePathStrategyColumns(std::vector<ColumnSpec> own) {
    std::vector<ColumnSpec> c = wholeTraversalColumns().group.specs();
    for (const ColumnSpec& col : wholePathColumns().group.specs()) c.push_back(col);
    for (ColumnSpec& col : own) {
        col.since = 19;
        c.push_back(col);
    }
    return c;
}

void writeWholePathColumns(const BatchPath& path, Row& row) {
    put(row, wholePathColumns().generations, path.generations.size());
    put(row, wholePathColumns().rays, path.rays());
}

}  // namespace rtbench
