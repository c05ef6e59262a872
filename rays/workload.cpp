#include "workload.h"

#include "device/gpu_buffers.h"
#include "structures/triangle_store.h"
#include "core/error.h"
#include "rays/shading.h"
#include "schema/column.h"

namespace rtbench {

ShadingInput Workload::generation(std::size_t g, const std::vector<gpu::Ray>& cameraRays) const {
    static const std::vector<std::uint32_t> noPaths;  // the camera rays: ray i's path is i
    static const std::vector<float> noWeights;        // and its weight 1
    if (g == 0) return {cameraRays, cameraHits, noPaths, noWeights};
    const Generation& before = between.at(g - 1);
    return {before.rays, before.hits, before.paths, before.weights};
}

std::uint32_t Workload::ancestor(std::uint32_t ray, std::size_t g) const {
    if (g >= between.size() + 1) return ray;
    ray = parents.at(ray);
    for (std::size_t k = between.size(); k > g; --k) ray = between[k - 1].parents.at(ray);
    return ray;
}

KeySpec randomSeedKey(const std::string& key, const std::string& who) {
    return {key, ValueType::Int, who + ": the seed of the random numbers (hashed with each ray's path and bounce)",
            ConfigValue{std::int64_t(0)}, false, 0, 4294967295.0};
}

void setSince(RayType& type, int schema) {
    for (KeySpec& k : type.keys) k.since = schema;
    for (ColumnSpec& c : type.columns) c.since = schema;
}

std::uint64_t countHits(const std::vector<gpu::HitRecord>& hits) {
    std::uint64_t n = 0;
    for (const gpu::HitRecord& h : hits) n += h.primitive != gpu::kNoHit;
    return n;
}

Workload followPaths(const WorkloadInputs& in, std::shared_ptr<const Surfaces> surfaces,
                     const std::vector<gpu::ShadingParams>& passes, std::uint32_t query,
                     const std::function<std::string(std::size_t, std::uint64_t, std::uint64_t)>& noRays) {
    Workload w;
    w.batch.query = query;
    w.shading = passes;
    w.surfaces = std::move(surfaces);
    w.cameraHits = in.structure.trace(in.cameraRays);
    for (std::size_t pass = 0; pass < passes.size(); ++pass) {
        const ShadingInput parents = w.generation(pass, in.cameraRays);
        // Refused before the rays are made: a fan-out (path.samples, ao.samples) multiplies them.
        refuseOversizedRayStream(std::uint64_t(parents.rays.size()) * passes[pass].pass.z);
        ShadedRays made = shadeOnCpu(in.scene, *w.surfaces, parents, passes[pass]);
        if (made.rays.empty()) throw Error(noRays(pass, parents.rays.size(), countHits(parents.hits)));
        if (pass + 1 == passes.size()) {
            w.parentRays = parents.rays.size();
            w.parentHits = countHits(parents.hits);
            w.batch.rays = std::move(made.rays);
            w.parents = std::move(made.parents);
            w.paths = std::move(made.paths);
            w.weights = std::move(made.weights);
            break;
        }
        Generation g{std::move(made.rays), {}, std::move(made.parents), std::move(made.paths), std::move(made.weights)};
        g.hits = in.structure.trace(g.rays);
        w.between.push_back(std::move(g));
    }
    w.pixels.resize(w.batch.rays.size());
    for (std::uint32_t r = 0; r < w.pixels.size(); ++r) w.pixels[r] = w.ancestor(r, 0);
    return w;
}

Workload followGenerations(const WorkloadInputs& in, Row& row, const std::vector<gpu::ShadingParams>& passes,
                           const std::string& type, const std::string& key, const std::string& noun, const ParentColumns& parents) {
    Workload w = followPaths(in, std::make_shared<const Surfaces>(), passes, gpu::kQueryClosest, [&](std::size_t pass, std::uint64_t rays, std::uint64_t) {
        return "rays.type = " + type + ": no rays at " + key + " " + std::to_string(pass + 1) + ": none of the " +
               std::to_string(rays) + " rays of " + noun + " " + std::to_string(pass) + " hit";
    });
    w.image = BatchImage::Hits;
    put(row, parents.rays, w.parentRays);
    put(row, parents.hits, w.parentHits);
    return w;
}

BatchPath batchPath(const Workload& w, const std::vector<gpu::Ray>& cameraRays, const TriangleMesh& scene) {
    BatchPath path;
    if (w.fromCamera()) {
        path.generations.push_back({&w.batch.rays});
    } else {
        path.generations.push_back({&cameraRays, &w.cameraHits});
        for (const Generation& g : w.between) path.generations.push_back({&g.rays, &g.hits, &g.parents, &g.paths, &g.weights});
        path.generations.push_back({&w.batch.rays, nullptr, &w.parents, &w.paths, &w.weights});
    }
    path.passes = w.shading;
    path.triangles = floatTriangles(scene);
    path.material = w.surfaces->materials.at(0);
    if (w.surfaces->materials.size() > 1 || !w.surfaces->materialOf.empty())
        path.notUniform = "surfaces have materials of their own";
    else if (!w.surfaces->lights.empty())
        path.notUniform = "shading passes read lights";
    return path;
}

namespace {

// The shading passes that made the rays after the first hit, run again on the device (results
// schema 9; 0 and empty for camera rays), declared once, here, where they are written.
struct ShadingColumns {
    using K = ColumnKind;
    ColumnGroup group;
    Column<std::uint64_t> passes = group.add<std::uint64_t>(
        {"shading_passes", K::Exact, "passes", "shading passes (kernels/shading.comp) that made the generations after the camera rays: 1 for shadow rays, k for reflection iteration k", 0.0, false, {}, 9});
    Column<std::uint64_t> rays = group.add<std::uint64_t>(
        {"shading_rays", K::Exact, "rays", "rays those passes made on the device, all generations together", 0.0, false, {}, 9});
    Column<double> ms = group.add<double>(
        {"shading_ms", K::Timing, "ms", "GPU time of those passes together (one dispatch each, not in kernel_ms)", 0.0, false, {}, 9});
    Column<std::uint64_t> mismatches = group.add<std::uint64_t>(
        {"shading_device_mismatches", K::Exact, "rays", "rays the device's shading passes made that differ from the CPU's in a bit, their parent or their path (a failed run)", 0.0, false, {}, 9});
};

const ShadingColumns& shadingColumnsDeclared() {
    static const ShadingColumns columns;
    return columns;
}

}  // namespace

const std::vector<ColumnSpec>& shadingColumns() { return shadingColumnsDeclared().group.specs(); }

std::string checkShadingOnDevice(VulkanContext& vk, unsigned workgroupSize, const TriangleMesh& scene,
                                 const std::vector<gpu::Ray>& cameraRays, const Workload& w, Row& row) {
    const std::vector<gpu::Triangle> triangles = floatTriangles(scene);  // once for every pass
    std::uint64_t made = 0, mismatches = 0;
    double ms = 0.0;
    bool timed = true;  // every pass has its GPU time (timestamps)
    std::string first;
    for (std::size_t g = 0; g < w.shading.size(); ++g) {
        // Generation g, and what the CPU made of it: generation g + 1.
        const ShadedRays cpu = g < w.between.size()
                                   ? ShadedRays{w.between[g].rays, w.between[g].parents, w.between[g].paths, w.between[g].weights}
                                   : ShadedRays{w.batch.rays, w.parents, w.paths, w.weights};
        double passMs = 0.0;
        const ShadedRays device =
            shadeOnDevice(vk, workgroupSize, triangles, *w.surfaces, w.generation(g, cameraRays), w.shading[g], passMs);
        made += device.rays.size();
        ms += passMs;
        timed = timed && passMs >= 0.0;
        std::string where;
        if (const std::uint64_t n = shadedMismatches(device, cpu, where)) {
            if (!mismatches) first = "generation " + std::to_string(g + 1) + ", " + where;
            mismatches += n;
        }
    }
    const ShadingColumns& c = shadingColumnsDeclared();
    put(row, c.passes, w.shading.size());
    put(row, c.rays, made);
    put(row, c.ms, timed && !w.shading.empty() ? std::optional<double>(ms) : std::nullopt);
    put(row, c.mismatches, mismatches);
    if (!mismatches) return "";
    return "the device's shading pass made rays that differ from the CPU's on " + std::to_string(mismatches) +
           " rays (first: " + first + ")";
}

}  // namespace rtbench
