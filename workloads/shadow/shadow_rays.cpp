#include "shadow_rays.h"

#include "structures/error.h"
#include "workloads/shading_reference.h"

namespace rtbench {

ShadowRays makeShadowRays(const TriangleMesh& scene, const std::vector<gpu::Ray>& rays,
                          const std::vector<gpu::HitRecord>& hits, glm::vec3 light) {
    shadingref::ShadingKernels k{};
    ShadowRays out;
    for (std::uint32_t i = 0; i < rays.size(); ++i) {
        const gpu::HitRecord& h = hits[i];
        if (h.primitive == gpu::kNoHit) continue;
        const glm::uvec3 t = scene.triangles.at(h.primitive);
        gpu::Ray shadow;
        if (k.rtShadowRay(scene.vertices[t.x], scene.vertices[t.y], scene.vertices[t.z], h.u, h.v,
                          glm::vec3(rays[i].directionTMax), light, shadow)) {
            out.rays.push_back(shadow);
            out.pixels.push_back(i);
        } else {
            ++out.unlit;
        }
    }
    return out;
}

glm::vec3 defaultLight(const Bounds3& box, glm::vec3 up) {
    const float upLength = glm::length(up);
    if (!(upLength > 0.0f)) throw Error("camera.up is the zero vector: no up to place the default light along");
    return (box.min + box.max) * 0.5f + up / upLength * glm::length(box.extent());
}

namespace {

Workload shadowWorkload(const WorkloadInputs& in, Row& row) {
    Workload w;
    w.batch.query = gpu::kQueryAny;
    w.cameraHits = in.structure.trace(in.cameraRays);
    const glm::vec3 light = [&in] {
        if (!in.run.has("light.position")) return defaultLight(in.scene.bounds(), in.cameraUp);
        const std::array<double, 3> given = in.run.getVec3("light.position");
        return in.toScene(glm::vec3(given[0], given[1], given[2]));
    }();
    ShadowRays shadow = makeShadowRays(in.scene, in.cameraRays, w.cameraHits, light);
    w.batch.rays = std::move(shadow.rays);
    w.pixels = std::move(shadow.pixels);
    w.parents = w.pixels;
    std::uint64_t cameraHits = 0;
    for (const gpu::HitRecord& h : w.cameraHits) cameraHits += h.primitive != gpu::kNoHit;
    row["camera_rays"] = std::to_string(in.cameraRays.size());
    row["camera_rays_hit"] = std::to_string(cameraHits);
    row["shadow_unlit"] = std::to_string(shadow.unlit);
    for (int a = 0; a < 3; ++a) row[std::string("light_") + char('x' + a)] = formatNumber(light[a], 9);
    if (w.batch.rays.empty())
        throw Error("rays.type = shadow: no shadow rays to trace (" + std::to_string(cameraHits) + " of " +
                    std::to_string(in.cameraRays.size()) + " camera rays hit, " + std::to_string(shadow.unlit) +
                    " of them with the light behind their surface)");
    return w;
}

}  // namespace

const RayType& shadowRayType() {
    static const RayType type = [] {
        using K = ColumnKind;
        RayType t;
        t.name = "shadow";
        t.help = "one any-hit ray from each camera ray's hit toward the point light (shadow casting)";
        t.keys = {{"light.position", ValueType::Float3,
                   "shadow rays: the point light, in the scene's own coordinates (moves with scene.scale and scene.translate; "
                   "default: above the scene box's centre along camera.up, one box diagonal away)",
                   {}}};
        t.columns = {
            {"camera_rays", K::Count, "rays", "shadow: camera rays (one per pixel) whose hits the shadow rays leave from"},
            {"camera_rays_hit", K::Count, "rays", "shadow: camera rays that hit (by the run's structure)"},
            {"shadow_unlit", K::Count, "rays", "shadow: hits with the light behind their surface: unlit, no shadow ray"},
            {"light_x", K::Count, "", "shadow: the point light in the traced scene (x)"},
            {"light_y", K::Count, "", "shadow: the point light (y)"},
            {"light_z", K::Count, "", "shadow: the point light (z)"},
        };
        t.make = shadowWorkload;
        for (ColumnSpec& c : t.columns) c.since = 7;
        for (KeySpec& k : t.keys) k.since = 7;
        return t;
    }();
    return type;
}

}  // namespace rtbench
