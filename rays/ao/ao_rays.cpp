#include "ao_rays.h"

#include "rays/shading.h"
#include "schema/column.h"

namespace rtbench {

namespace {

// Ambient occlusion's own columns (results schema 9), declared once, here, where they are written.
struct AoColumns {
    ColumnGroup group;
    Column<double> radiusTraced = group.add<double>(
        {"ao_radius_traced", ColumnKind::Exact, "scene units", "ao: the rays' length in the traced scene", 0.0, false, {}, 9}, 9);
    Column<std::uint64_t> cameraHits = group.add<std::uint64_t>(
        {"ao_camera_hits", ColumnKind::Exact, "rays", "ao: camera rays that hit; each makes ao.samples rays", 0.0, false, {}, 9});
};

const AoColumns& aoColumns() {
    static const AoColumns columns;
    return columns;
}

Workload aoWorkload(const WorkloadInputs& in, Row& row) {
    const auto samples = std::uint32_t(in.run.getInt("ao.samples"));
    const auto seed = std::uint32_t(in.run.getInt("ao.seed"));
    // Given in the scene's own units, it scales with it; by default a tenth of the traced scene's diagonal.
    const float radius = in.run.has("ao.radius") ? float(in.run.getFloat("ao.radius") * in.run.getFloat("scene.scale"))
                                                 : 0.1f * glm::length(in.scene.bounds().extent());
    put(row, aoColumns().radiusTraced, radius);
    Workload w = followPaths(in, std::make_shared<const Surfaces>(), {diffusePass(samples, 1, seed, radius)}, gpu::kQueryAny,
                             [](std::size_t, std::uint64_t rays, std::uint64_t) {
                                 return "rays.type = ao: no rays to trace: none of the " + std::to_string(rays) +
                                        " camera rays hit";
                             });
    put(row, aoColumns().cameraHits, w.parentHits);
    return w;
}

}  // namespace

const RayType& aoRayType() {
    static const RayType type = [] {
        RayType t;
        t.name = "ao";
        t.help = "ambient occlusion: ao.samples any-hit cosine-weighted rays of length ao.radius from each camera hit";
        t.perCameraRayKey = "ao.samples";
        t.keys = {
            {"ao.samples", ValueType::Int, "ambient-occlusion rays per camera hit", ConfigValue{std::int64_t(4)}, false, 1, 256},
            {"ao.radius", ValueType::Float,
             "ambient occlusion: the rays' length, in the scene's own units (moves with scene.scale; default: a tenth of "
             "the scene box's diagonal)",
             {}, false, 1e-30, 1e30},
            randomSeedKey("ao.seed", "ambient occlusion"),
        };
        t.columns = aoColumns().group.specs();
        t.make = aoWorkload;
        setSince(t, 9);
        return t;
    }();
    return type;
}

}  // namespace rtbench
