#include "reflection_rays.h"

#include "rays/shading.h"

namespace rtbench {

namespace {

Workload reflectionWorkload(const WorkloadInputs& in, Row& row) {
    const auto iteration = std::size_t(in.run.getInt("reflection.iteration"));
    return followGenerations(in, row, std::vector<gpu::ShadingParams>(iteration, mirrorPass()), "reflection",
                             "reflection.iteration", "iteration");
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
            {"reflection_parent_rays", K::Exact, "rays", "reflection: rays of the iteration before (1: the camera rays)"},
            {"reflection_parent_hits", K::Exact, "rays", "reflection: of those, the rays that hit: each makes one ray"},
        };
        t.make = reflectionWorkload;
        setSince(t, 8);
        return t;
    }();
    return type;
}

}  // namespace rtbench
