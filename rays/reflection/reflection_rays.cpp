#include "reflection_rays.h"

#include "rays/shading.h"

namespace rtbench {

namespace {

const ParentColumns& reflectionColumns() {
    static const ParentColumns columns("reflection", "reflection: rays of the iteration before (1: the camera rays)",
                                       "reflection: of those, the rays that hit: each makes one ray", 8);
    return columns;
}

Workload reflectionWorkload(const WorkloadInputs& in, Row& row) {
    const auto iteration = std::size_t(in.run.getInt("reflection.iteration"));
    return followGenerations(in, row, std::vector<gpu::ShadingParams>(iteration, mirrorPass()), "reflection",
                             "reflection.iteration", "iteration", reflectionColumns());
}

}  // namespace

const RayType& reflectionRayType() {
    static const RayType type = [] {
        RayType t;
        t.name = "reflection";
        t.help = "the mirror reflections of the previous iteration's hits, every surface a mirror (Christen 2005 §5.2.1)";
        t.keys = {{"reflection.iteration", ValueType::Int,
                   "reflection rays: the iteration traced (1: the camera hits' reflections; k: those of iteration k - 1's "
                   "hits, the earlier iterations traced by the run's structure)",
                   ConfigValue{std::int64_t(1)}, false, 1, 64}};
        t.columns = reflectionColumns().group.specs();
        t.make = reflectionWorkload;
        setSince(t, 8);
        return t;
    }();
    return type;
}

}  // namespace rtbench
