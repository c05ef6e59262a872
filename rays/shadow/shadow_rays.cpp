#include "shadow_rays.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "scene/scene_limits.h"
#include "rays/shading.h"

namespace rtbench {

glm::vec3 defaultLight(const Bounds3& box, glm::vec3 up) {
    const float upLength = glm::length(up);
    if (!(upLength > 0.0f)) throw Error("camera.up is the zero vector: no up to place the default light along");
    return (box.min + box.max) * 0.5f + up / upLength * glm::length(box.extent());
}

glm::vec3 reachableLight(glm::vec3 light, const Bounds3& box, const std::string& what) {
    for (int a = 0; a < 3; ++a) {
        const double farthest = std::max(std::abs(double(light[a]) - box.min[a]), std::abs(double(light[a]) - box.max[a]));
        if (!(farthest <= double(kMaxDirectionComponent)))
            throw Error(what + " (" + formatFloat(light.x) + ", " + formatFloat(light.y) + ", " + formatFloat(light.z) +
                        " in the traced scene) is " + formatFloat(farthest) + " from the scene's box along " + char('x' + a) +
                        ": a shadow ray's direction (light - point) may not exceed " + formatFloat(kMaxDirectionComponent) +
                        " per component; bring the light nearer the scene");
    }
    return light;
}

namespace {

Workload shadowWorkload(const WorkloadInputs& in, Row& row) {
    const glm::vec3 light = [&in] {
        if (!in.run.has("light.position")) return defaultLight(in.scene.bounds(), in.cameraUp);
        const std::array<double, 3> given = in.run.getVec3("light.position");
        return reachableLight(in.toScene(glm::vec3(given[0], given[1], given[2])), in.scene.bounds(), "light.position");
    }();
    for (int a = 0; a < 3; ++a) row[std::string("light_") + char('x' + a)] = formatNumber(light[a], 9);
    row["camera_rays"] = std::to_string(in.cameraRays.size());
    auto surfaces = std::make_shared<Surfaces>();
    surfaces->lights = {light};
    Workload w = followPaths(in, std::move(surfaces), {shadowPass(1)}, gpu::kQueryAny, [](std::size_t, std::uint64_t rays, std::uint64_t hits) {
        return "rays.type = shadow: no shadow rays to trace (" +
               (hits ? std::to_string(hits) + " of " + std::to_string(rays) + " camera rays hit, all with the light behind their surface)"
                     : "none of the " + std::to_string(rays) + " camera rays hit)");
    });
    row["camera_rays_hit"] = std::to_string(w.parentHits);
    row["shadow_unlit"] = std::to_string(w.parentHits - w.batch.rays.size());
    return w;
}

}  // namespace

KeySpec lightPositionKey() {
    KeySpec light{"light.position", ValueType::Float3, "shadow and whitted rays: the point light, in the scene's own coordinates (moves with scene.scale and scene.translate; default: above the scene box's centre along camera.up, one box diagonal away; whitted: a scene description's [[light]]s instead, when it has them)", {}};
    light.since = 7;
    return light;
}

const RayType& shadowRayType() {
    static const RayType type = [] {
        using K = ColumnKind;
        RayType t;
        t.name = "shadow";
        t.help = "one any-hit ray from each camera ray's hit toward the point light (shadow casting)";
        t.keys = {lightPositionKey()};  // whitted reads it too
        t.columns = {
            {"camera_rays", K::Exact, "rays", "shadow: camera rays (one per pixel) whose hits the shadow rays leave from"},
            {"camera_rays_hit", K::Exact, "rays", "shadow: camera rays that hit (by the run's structure)"},
            {"shadow_unlit", K::Exact, "rays", "shadow: hits with the light behind their surface: unlit, no shadow ray"},
            {"light_x", K::Exact, "", "shadow: the point light in the traced scene (x)"},
            {"light_y", K::Exact, "", "shadow: the point light (y)"},
            {"light_z", K::Exact, "", "shadow: the point light (z)"},
        };
        t.make = shadowWorkload;
        setSince(t, 7);
        return t;
    }();
    return type;
}

}  // namespace rtbench
