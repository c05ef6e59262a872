#include "shadow_rays.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "scene/scene_limits.h"
#include "rays/shading.h"
#include "schema/column.h"

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

// Shadow rays' own columns (results schema 7), declared once, here, where they are written.
struct ShadowColumns {
    using K = ColumnKind;
    using U64 = std::uint64_t;
    ColumnGroup group;
    Column<U64> cameraRays = group.add<U64>({"camera_rays", K::Exact, "rays", "shadow: camera rays (one per pixel) whose hits the shadow rays leave from", 0.0, false, {}, 7});
    Column<U64> cameraRaysHit = group.add<U64>({"camera_rays_hit", K::Exact, "rays", "shadow: camera rays that hit (by the run's structure)", 0.0, false, {}, 7});
    Column<U64> unlit = group.add<U64>({"shadow_unlit", K::Exact, "rays", "shadow: hits with the light behind their surface: unlit, no shadow ray", 0.0, false, {}, 7});
    std::array<Column<double>, 3> light = {
        group.add<double>({"light_x", K::Exact, "", "shadow: the point light in the traced scene (x)", 0.0, false, {}, 7}, 9),
        group.add<double>({"light_y", K::Exact, "", "shadow: the point light (y)", 0.0, false, {}, 7}, 9),
        group.add<double>({"light_z", K::Exact, "", "shadow: the point light (z)", 0.0, false, {}, 7}, 9)};
};

const ShadowColumns& shadowColumns() {
    static const ShadowColumns columns;
    return columns;
}

Workload shadowWorkload(const WorkloadInputs& in, Row& row) {
    const glm::vec3 light = [&in] {
        if (!in.run.has("light.position")) return defaultLight(in.scene.bounds(), in.cameraUp);
        const std::array<double, 3> given = in.run.getVec3("light.position");
        return reachableLight(in.toScene(glm::vec3(given[0], given[1], given[2])), in.scene.bounds(), "light.position");
    }();
    const ShadowColumns& c = shadowColumns();
    for (int a = 0; a < 3; ++a) put(row, c.light[std::size_t(a)], light[a]);
    put(row, c.cameraRays, in.cameraRays.size());
    auto surfaces = std::make_shared<Surfaces>();
    surfaces->lights = {light};
    Workload w = followPaths(in, std::move(surfaces), {shadowPass(1)}, gpu::kQueryAny, [](std::size_t, std::uint64_t rays, std::uint64_t hits) {
        return "rays.type = shadow: no shadow rays to trace (" +
               (hits ? std::to_string(hits) + " of " + std::to_string(rays) + " camera rays hit, all with the light behind their surface)"
                     : "none of the " + std::to_string(rays) + " camera rays hit)");
    });
    put(row, c.cameraRaysHit, w.parentHits);
    put(row, c.unlit, w.parentHits - w.batch.rays.size());
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
        RayType t;
        t.name = "shadow";
        t.help = "one any-hit ray from each camera ray's hit toward the point light (shadow casting)";
        t.keys = {lightPositionKey()};  // whitted reads it too
        t.columns = shadowColumns().group.specs();
        t.make = shadowWorkload;
        setSince(t, 7);
        return t;
    }();
    return type;
}

}  // namespace rtbench
