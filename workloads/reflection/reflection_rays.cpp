#include "reflection_rays.h"

#include "structures/error.h"
#include "workloads/shading_reference.h"

namespace rtbench {

ReflectedRays makeReflectedRays(const TriangleMesh& scene, const std::vector<gpu::Ray>& rays,
                                const std::vector<gpu::HitRecord>& hits) {
    shadingref::ShadingKernels k{};
    ReflectedRays out;
    for (std::uint32_t i = 0; i < rays.size(); ++i) {
        const gpu::HitRecord& h = hits[i];
        if (h.primitive == gpu::kNoHit) continue;
        const glm::uvec3 t = scene.triangles.at(h.primitive);
        gpu::Ray reflected;
        if (!k.rtReflectRay(scene.vertices[t.x], scene.vertices[t.y], scene.vertices[t.z], h.u, h.v,
                            glm::vec3(rays[i].directionTMax), reflected))
            continue;
        out.rays.push_back(reflected);
        out.parents.push_back(i);
    }
    return out;
}

namespace {

std::uint64_t countHits(const std::vector<gpu::HitRecord>& hits) {
    std::uint64_t n = 0;
    for (const gpu::HitRecord& h : hits) n += h.primitive != gpu::kNoHit;
    return n;
}

Workload reflectionWorkload(const WorkloadInputs& in, Row& row) {
    const std::int64_t iteration = in.run.getInt("reflection.iteration");
    Workload w;
    w.batch.query = gpu::kQueryClosest;
    w.image = BatchImage::Hits;
    w.cameraHits = in.structure.trace(in.cameraRays);
    const std::vector<gpu::Ray>* previousRays = &in.cameraRays;
    const std::vector<gpu::HitRecord>* previousHits = &w.cameraHits;
    for (std::int64_t i = 1;; ++i) {
        ReflectedRays reflected = makeReflectedRays(in.scene, *previousRays, *previousHits);
        if (reflected.rays.empty())
            throw Error("rays.type = reflection: no rays at reflection.iteration " + std::to_string(i) + ": none of the " +
                        std::to_string(previousRays->size()) + " rays of iteration " + std::to_string(i - 1) + " hit");
        if (i == iteration) {
            row["reflection_parent_rays"] = std::to_string(previousRays->size());
            row["reflection_parent_hits"] = std::to_string(countHits(*previousHits));
            w.batch.rays = std::move(reflected.rays);
            w.parents = std::move(reflected.parents);
            break;
        }
        Generation g{std::move(reflected.rays), {}, std::move(reflected.parents)};
        g.hits = in.structure.trace(g.rays);
        w.between.push_back(std::move(g));
        previousRays = &w.between.back().rays;
        previousHits = &w.between.back().hits;
    }
    // Each ray's pixel: its parents' chain back to the camera ray.
    w.pixels.resize(w.parents.size());
    for (std::size_t r = 0; r < w.parents.size(); ++r) {
        std::uint32_t ray = w.parents[r];
        for (std::size_t g = w.between.size(); g-- > 0;) ray = w.between[g].parents[ray];
        w.pixels[r] = ray;
    }
    return w;
}

}  // namespace

const RayType& reflectionRayType() {
    static const RayType type = [] {
        using K = ColumnKind;
        RayType t;
        t.name = "reflection";
        t.help = "the mirror reflections of the previous iteration's hits, every surface a mirror (Christen 2005 §5.2.1)";
        t.keys = {{"reflection.iteration", ValueType::Int,
                   "reflection rays: the iteration traced (1: the camera hits' reflections; k: those of iteration k - 1's "
                   "hits, the earlier iterations traced by the run's structure)",
                   ConfigValue{std::int64_t(1)}, false, 1, 64}};
        t.columns = {
            {"reflection_parent_rays", K::Count, "rays", "reflection: rays of the iteration before (1: the camera rays)"},
            {"reflection_parent_hits", K::Count, "rays", "reflection: of those, the rays that hit: each makes one ray"},
        };
        t.make = reflectionWorkload;
        for (ColumnSpec& c : t.columns) c.since = 8;
        for (KeySpec& k : t.keys) k.since = 8;
        return t;
    }();
    return type;
}

}  // namespace rtbench
