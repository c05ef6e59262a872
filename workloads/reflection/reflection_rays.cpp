#include "reflection_rays.h"

#include "workloads/shading.h"

namespace rtbench {

namespace {

Workload reflectionWorkload(const WorkloadInputs& in, Row& row) {
    const std::int64_t iteration = in.run.getInt("reflection.iteration");
    Workload w = followPaths(in, std::vector<gpu::ShadingParams>(std::size_t(iteration), mirrorPass()), gpu::kQueryClosest,
                             [](std::size_t pass, std::uint64_t rays, std::uint64_t) {
                                 return "rays.type = reflection: no rays at reflection.iteration " + std::to_string(pass + 1) +
                                        ": none of the " + std::to_string(rays) + " rays of iteration " +
                                        std::to_string(pass) + " hit";
                             });
    w.image = BatchImage::Hits;
    row["reflection_parent_rays"] = std::to_string(w.parentRays);
    row["reflection_parent_hits"] = std::to_string(w.parentHits);
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
        setSince(t, 8);
        return t;
    }();
    return type;
}

}  // namespace rtbench
