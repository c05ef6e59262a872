#include "refraction_rays.h"

#include "rays/shading.h"

namespace rtbench {

std::uint64_t countTotalInternalReflections(const TriangleMesh& scene, const std::vector<gpu::Ray>& cameraRays,
                                            const Workload& w) {
    // The generation the batch was made from: its rays and their hits.
    const std::vector<gpu::Ray>& rays = w.between.empty() ? cameraRays : w.between.back().rays;
    const std::vector<gpu::HitRecord>& hits = w.between.empty() ? w.cameraHits : w.between.back().hits;
    std::uint64_t reflected = 0;
    for (std::size_t r = 0; r < w.batch.rays.size(); ++r) {
        const std::uint32_t parent = w.parents[r];
        const glm::uvec3 t = scene.triangles.at(hits.at(parent).primitive);
        const glm::dvec3 v0(scene.vertices[t.x]), n = glm::cross(glm::dvec3(scene.vertices[t.y]) - v0,
                                                                 glm::dvec3(scene.vertices[t.z]) - v0);
        const double before = glm::dot(n, glm::dvec3(rays[parent].directionTMax));
        const double after = glm::dot(n, glm::dvec3(w.batch.rays[r].directionTMax));
        reflected += (before < 0.0) != (after < 0.0);
    }
    return reflected;
}

namespace {

// Refraction's own columns (results schema 9): the iteration the batch was made from, and the
// rays total internal reflection turned back.
struct RefractionColumns {
    ParentColumns parents{"refraction", "refraction: rays of the iteration before (1: the camera rays)",
                          "refraction: of those, the rays that hit: each makes one ray", 9};
    Column<std::uint64_t> totalInternal{{"refraction_total_internal", ColumnKind::Exact, "rays",
                                         "refraction: rays reflected past the critical angle (total internal reflection) instead of transmitted",
                                         0.0, false, {}, 9}};
    std::vector<ColumnSpec> specs() const {
        std::vector<ColumnSpec> s = parents.group.specs();
        s.push_back(totalInternal.spec());
        return s;
    }
};

const RefractionColumns& refractionColumns() {
    static const RefractionColumns columns;
    return columns;
}

Workload refractionWorkload(const WorkloadInputs& in, Row& row) {
    const auto iteration = std::size_t(in.run.getInt("refraction.iteration"));
    const auto ior = float(in.run.getFloat("refraction.ior"));
    Workload w = followGenerations(in, row, std::vector<gpu::ShadingParams>(iteration, refractPass(ior)), "refraction",
                                   "refraction.iteration", "iteration", refractionColumns().parents);
    put(row, refractionColumns().totalInternal, countTotalInternalReflections(in.scene, in.cameraRays, w));
    return w;
}

}  // namespace

const RayType& refractionRayType() {
    static const RayType type = [] {
        RayType t;
        t.name = "refraction";
        t.help = "the refractions of the previous iteration's hits, every surface glass (total internal reflection: the mirror ray)";
        t.keys = {
            {"refraction.iteration", ValueType::Int,
             "refraction rays: the iteration traced (1: the camera hits' refractions; k: those of iteration k - 1's hits, "
             "the earlier iterations traced by the run's structure)",
             ConfigValue{std::int64_t(1)}, false, 1, 64},
            {"refraction.ior", ValueType::Float,
             "refraction rays: the index of refraction of every surface against 1 outside (glass: 1.5)", ConfigValue{1.5},
             false, 0.01, 100},
        };
        t.columns = refractionColumns().specs();
        t.make = refractionWorkload;
        setSince(t, 9);
        return t;
    }();
    return type;
}

}  // namespace rtbench
