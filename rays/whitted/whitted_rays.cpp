#include "whitted_rays.h"

#include "core/error.h"
#include "rays/shadow/shadow_rays.h"
#include "schema/column.h"

namespace rtbench {

std::shared_ptr<const Surfaces> whittedSurfaces(const WorkloadInputs& in) {
    const Appearance& look = in.scene.appearance;
    if (look.materialsLost)
        throw Error("rays.type = whitted: the scene description's materials do not survive scene.simplify_* (which "
                    "triangle of the simplified scene has which material is not known); trace it unsimplified");
    auto s = std::make_shared<Surfaces>();
    const std::string surface = in.run.getString("whitted.surface");
    s->materials = {surface == "diffuse" ? diffuseMaterial()
                    : surface == "mirror" ? mirrorMaterial(float(in.run.getFloat("whitted.reflectance")))
                                          : glassMaterial(float(in.run.getFloat("whitted.ior")))};
    for (const DescribedMaterial& m : look.materials)
        s->materials.push_back(m.kind == MaterialKind::Diffuse  ? diffuseMaterial(glm::vec3(m.colour))
                               : m.kind == MaterialKind::Mirror ? mirrorMaterial(float(m.reflectance), glm::vec3(m.colour))
                                                                : glassMaterial(float(m.ior)));
    if (!look.materialOf.empty()) {
        if (look.materialOf.size() != in.scene.triangles.size())
            throw Error("rays.type = whitted: materials for " + std::to_string(look.materialOf.size()) + " triangles, the scene has " +
                        std::to_string(in.scene.triangles.size()));
        s->materialOf.reserve(look.materialOf.size());
        for (std::uint32_t m : look.materialOf) s->materialOf.push_back(m == kUndescribedMaterial ? 0 : m + 1);
    }
    if (!look.lights.empty()) {
        if (in.run.has("light.position"))
            throw Error("light.position: the scene description gives " + std::to_string(look.lights.size()) +
                        " [[light]] tables, which light a whitted run; give one or the other");
        for (std::size_t k = 0; k < look.lights.size(); ++k)
            s->lights.push_back(reachableLight(in.toScene(glm::vec3(look.lights[k])), in.scene.bounds(),
                                               "the scene description's [[light]] " + std::to_string(k + 1)));
    } else if (in.run.has("light.position")) {
        const std::array<double, 3> given = in.run.getVec3("light.position");
        s->lights.push_back(reachableLight(in.toScene(glm::vec3(given[0], given[1], given[2])), in.scene.bounds(), "light.position"));
    } else {
        s->lights.push_back(defaultLight(in.scene.bounds(), in.cameraUp));
    }
    return s;
}

namespace {

// Whitted rays' own columns (results schema 10), declared once, here, where they are written.
struct WhittedColumns {
    using K = ColumnKind;
    using U64 = std::uint64_t;
    ColumnGroup group;
    Column<U64> lights = group.add<U64>({"whitted_lights", K::Exact, "lights", "whitted: point lights (each diffuse hit makes a shadow ray toward each)", 0.0, false, {}, 10});
    Column<std::string> lightPositions = group.add<std::string>(
        {"whitted_light_positions", K::Exact, "scene units", "whitted: the point lights in the traced scene, \"x y z\" each, separated by \"; \"", 0.0, false, {}, 10});
    Column<U64> materials = group.add<U64>({"whitted_materials", K::Exact, "materials", "whitted: materials (whitted.surface and the description's)", 0.0, false, {}, 10});
    Column<U64> parentRays = group.add<U64>({"whitted_parent_rays", K::Exact, "rays", "whitted: rays of the generation the batch was made from", 0.0, false, {}, 10});
    Column<U64> parentHits = group.add<U64>({"whitted_parent_hits", K::Exact, "rays", "whitted: of those, the rays that hit", 0.0, false, {}, 10});
    Column<U64> raysBefore = group.add<U64>(
        {"whitted_rays_before", K::Exact, "rays", "whitted: rays traced before the batch (the camera rays and generations 1 .. whitted.depth - 1 or .. depth)", 0.0, false, {}, 10});
    Column<U64> reflected = group.add<U64>({"whitted_reflected", K::Exact, "rays", "whitted (secondary): batch rays that are reflections", 0.0, false, {}, 10});
    Column<U64> refracted = group.add<U64>({"whitted_refracted", K::Exact, "rays", "whitted (secondary): batch rays that are refractions", 0.0, false, {}, 10});
    Column<double> weight = group.add<double>(
        {"whitted_weight", K::Exact, "", "whitted: the sum of the batch rays' weights (the pixels' worth of radiance they carry)", 0.0, false, {}, 10}, 9);
};

const WhittedColumns& whittedColumns() {
    static const WhittedColumns columns;
    return columns;
}

// The batch's lights, materials and generations into the row; a shadow batch has no reflections
// or refractions (empty).
void writeWhittedColumns(const WorkloadInputs& in, const Surfaces& surfaces, const Workload& w, bool shadow, Row& row) {
    const WhittedColumns& c = whittedColumns();
    put(row, c.lights, surfaces.lights.size());
    std::string positions;  // in the traced scene
    for (const glm::vec3& l : surfaces.lights)
        positions += (positions.empty() ? "" : "; ") + formatNumber(l.x, 9) + " " + formatNumber(l.y, 9) + " " + formatNumber(l.z, 9);
    put(row, c.lightPositions, positions);
    put(row, c.materials, surfaces.materials.size());
    put(row, c.parentRays, w.parentRays);
    put(row, c.parentHits, w.parentHits);
    std::uint64_t traced = in.cameraRays.size();
    for (const Generation& g : w.between) traced += g.rays.size();
    put(row, c.raysBefore, traced);
    // A secondary ray's slot (path mod 2) says which it is: 0 the reflection, 1 the refraction.
    std::uint64_t refracted = 0;
    double weight = 0.0;
    for (std::size_t r = 0; r < w.batch.rays.size(); ++r) {
        refracted += !shadow && w.paths[r] % 2 == 1;
        weight += double(w.weights[r]);
    }
    put(row, c.reflected, shadow ? std::nullopt : std::optional<std::uint64_t>(w.batch.rays.size() - refracted));
    put(row, c.refracted, shadow ? std::nullopt : std::optional<std::uint64_t>(refracted));
    put(row, c.weight, weight);
}

Workload whittedWorkload(const WorkloadInputs& in, Row& row) {
    const auto depth = std::size_t(in.run.getInt("whitted.depth"));
    const bool shadow = in.run.getString("whitted.rays") == "shadow";
    if (!shadow && depth == 0)
        throw Error("whitted.depth = 0 with whitted.rays = secondary: generation 0 is the camera rays (rays.type = "
                    "primary); reflections and refractions start at depth 1");
    std::shared_ptr<const Surfaces> surfaces = whittedSurfaces(in);
    const auto lights = std::uint32_t(surfaces->lights.size());
    std::vector<gpu::ShadingParams> passes(depth, specularPass());
    if (shadow) passes.push_back(shadowPass(lights));
    Workload w = followPaths(in, surfaces, passes, shadow ? gpu::kQueryAny : gpu::kQueryClosest,
                             [&](std::size_t pass, std::uint64_t rays, std::uint64_t hits) {
                                 const bool shadows = pass == depth;
                                 return "rays.type = whitted: no " +
                                        std::string(shadows ? "shadow rays from" : "reflections or refractions of") +
                                        " generation " + std::to_string(pass) + " (whitted.depth = " +
                                        std::to_string(depth) + "): of its " + std::to_string(rays) + " rays " +
                                        std::to_string(hits) + " hit, " +
                                        (shadows ? "none on a surface with a diffuse part and a light in front of it"
                                                 : "none on a mirror or glass");
                             });
    w.image = shadow ? BatchImage::Shadows : BatchImage::Hits;
    writeWhittedColumns(in, *surfaces, w, shadow, row);
    return w;
}

}  // namespace

const RayType& whittedRayType() {
    static const RayType type = [] {
        RayType t;
        t.name = "whitted";
        t.help = "Whitted ray tracing by material: generation whitted.depth's reflections and refractions, or the "
                 "shadow rays of its hits";
        t.planned = PlannedRays::About;
        KeySpec reflectance{"whitted.reflectance", ValueType::Float,
                            "whitted rays: the reflectance of whitted.surface = mirror (the rest diffuse)",
                            ConfigValue{0.5}, false, 0.001, 1};
        reflectance.appliesWhen = {"whitted.surface=mirror"};
        KeySpec ior{"whitted.ior", ValueType::Float, "whitted rays: the index of refraction of whitted.surface = glass",
                    ConfigValue{1.5}, false, 0.01, 100};
        ior.appliesWhen = {"whitted.surface=glass"};
        t.keys = {
            {"whitted.depth", ValueType::Int,
             "whitted rays: the generation (0: the camera rays; k: the reflections and refractions of generation k - 1's "
             "hits, the earlier generations traced by the run's structure)",
             ConfigValue{std::int64_t(1)}, false, 0, 32},
            {"whitted.rays", ValueType::String,
             "whitted rays: the batch measured: secondary (generation whitted.depth itself, closest hit; depth >= 1) or "
             "shadow (a ray toward each light from its hits, any hit)",
             ConfigValue{std::string("secondary")}, false, -1e300, 1e300, {"secondary", "shadow"}},
            {"whitted.surface", ValueType::String,
             "whitted rays: the material of every surface a scene description's [[material]] does not cover: diffuse, "
             "mirror (whitted.reflectance) or glass (whitted.ior)",
             ConfigValue{std::string("mirror")}, false, -1e300, 1e300, {"diffuse", "mirror", "glass"}},
            reflectance,
            ior,
        };
        t.columns = whittedColumns().group.specs();
        t.make = whittedWorkload;
        setSince(t, 10);
        t.keys.push_back(lightPositionKey());  // the shadow rays' light, since results schema 7
        return t;
    }();
    return type;
}

}  // namespace rtbench
