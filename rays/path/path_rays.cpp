#include "path_rays.h"

#include "rays/shading.h"

namespace rtbench {

namespace {

const ParentColumns& pathColumns() {
    static const ParentColumns columns("path", "path: rays of the bounce before (1: the camera rays)",
                                       "path: of those, the rays that hit (bounce 1: each starts path.samples paths)", 9);
    return columns;
}

Workload pathWorkload(const WorkloadInputs& in, Row& row) {
    const auto bounce = std::uint32_t(in.run.getInt("path.bounce"));
    const auto samples = std::uint32_t(in.run.getInt("path.samples"));
    const auto seed = std::uint32_t(in.run.getInt("path.seed"));
    // Bounce 1 starts `samples` paths at each camera hit; later bounces go on with one ray each.
    std::vector<gpu::ShadingParams> passes;
    for (std::uint32_t b = 1; b <= bounce; ++b) passes.push_back(diffusePass(b == 1 ? samples : 1, b, seed, gpu::kNoHitT));
    return followGenerations(in, row, passes, "path", "path.bounce", "bounce", pathColumns());
}

}  // namespace

const RayType& pathRayType() {
    static const RayType type = [] {
        RayType t;
        t.name = "path";
        t.help = "diffuse path tracing: cosine-weighted bounces from the previous bounce's hits, every surface diffuse";
        t.perCameraRayKey = "path.samples";
        t.keys = {
            {"path.bounce", ValueType::Int,
             "path rays: the bounce traced (1: rays leaving the camera hits; k: those leaving bounce k - 1's hits, the "
             "earlier bounces traced by the run's structure)",
             ConfigValue{std::int64_t(1)}, false, 1, 64},
            {"path.samples", ValueType::Int, "path rays: paths per pixel (each camera hit starts this many)",
             ConfigValue{std::int64_t(1)}, false, 1, 1024},
            randomSeedKey("path.seed", "path rays"),
        };
        t.columns = pathColumns().group.specs();
        t.make = pathWorkload;
        setSince(t, 9);
        return t;
    }();
    return type;
}

}  // namespace rtbench
