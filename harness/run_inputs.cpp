#include "run_inputs.h"

#include "core/error.h"
#include "scene/procedural.h"
#include "scene/scene_description.h"
#include "scene/scene_limits.h"
#include "scene/simplify.h"
#include "structures/triangle_store.h"
#include "schema/column.h"
#include "run_columns.h"
#include "schema/warnings.h"

namespace rtbench {

glm::vec3 toVec3(const std::array<double, 3>& a) { return glm::vec3(float(a[0]), float(a[1]), float(a[2])); }

VulkanContext& deviceFor(const RunConfig& run, Caches& caches) {
    const std::string deviceName = run.getString("device.name");
    const bool validation = run.getBool("device.validation");
    const std::string deviceKey = deviceName + (validation ? "+validation" : "");
    if (!caches.devices.count(deviceKey)) caches.devices[deviceKey] = std::make_shared<VulkanContext>(deviceName, validation);
    return *caches.devices[deviceKey];
}

glm::vec3 sceneTransform(const RunConfig& run, glm::vec3 p) {
    const float scale = float(run.getFloat("scene.scale"));
    const glm::vec3 translate = toVec3(run.getVec3("scene.translate"));
    return p * scale + translate;
}

std::string sceneKey(const RunConfig& run) {
    return run.getString("scene.source") + "|" + formatValue(run.values.at("scene.scale")) + "|" +
           formatValue(run.values.at("scene.translate"));
}

const std::shared_ptr<TriangleMesh>& fullScene(const ExperimentPlan& plan, const RunConfig& run, Caches& caches) {
    const std::string key = sceneKey(run);
    if (!caches.meshes.count(key)) {
        TriangleMesh mesh = loadSceneSource(run.getString("scene.source"), plan.configDir);
        for (glm::vec3& v : mesh.vertices) v = sceneTransform(run, v);
        caches.meshes[key] = std::make_shared<TriangleMesh>(std::move(mesh));
    }
    return caches.meshes[key];
}

namespace {

// The scene as the methods trace it, declared once, here, where its values are written.
struct SceneInputColumns {
    using K = ColumnKind;
    using U64 = std::uint64_t;
    ColumnGroup group;
    Column<U64> triangles = group.add<U64>({"scene_triangles", K::Exact, "triangles", "triangles after triangulation"});
    Column<U64> degenerate = group.add<U64>({"scene_degenerate", K::Exact, "triangles", "zero-area triangles in float (never hit)"});
    Column<U64> fullTriangles = group.add<U64>(
        {"scene_full_triangles", K::Exact, "triangles", "triangles of the scene before scene.simplify_*: what the exact reference traces"});
    Column<double> simplifyMs = group.add<double>({"scene_simplify_ms", K::Timing, "ms", "scene.simplify_*: wall time of the edge collapses"}, 4);
    Column<double> latticeStep = group.add<double>(
        {"vertex_lattice_step", K::Exact, "scene units", "intersection.vertex_bits < 32: the spacing of the vertex lattice"});
    Column<double> snapErrorMax = group.add<double>(
        {"vertex_snap_error_max", K::Exact, "scene units", "intersection.vertex_bits < 32: the largest distance a vertex moved to its lattice point (not simplified scenes)"}, 4);
};

const SceneInputColumns& sceneInputs() {
    static const SceneInputColumns columns;
    return columns;
}

// Embree as the run used it.
struct EmbreeColumns {
    using K = ColumnKind;
    ColumnGroup group;
    Column<int> threads = group.add<int>({"embree_threads", K::Context, "threads", "TBB threads Embree ran on"});
    Column<std::string> isa = group.add<std::string>({"embree_isa", K::Context, "", "Embree's native packet width (its ISA path)"});
    Column<double> buildMs = group.add<double>({"embree_build_ms", K::Timing, "ms", "Embree BVH build time"}, 4);
};

const EmbreeColumns& embreeColumnsDeclared() {
    static const EmbreeColumns columns;
    return columns;
}

}  // namespace

const std::vector<ColumnSpec>& sceneInputColumns() { return sceneInputs().group.specs(); }
const std::vector<ColumnSpec>& embreeColumns() { return embreeColumnsDeclared().group.specs(); }

void writeInputColumns(const TriangleMesh& scene, Row& row) {
    put(row, runColumnsDeclared().inputsHash, inputsHash(scene.inputs));
    std::string files;
    for (const InputFile& f : scene.inputs)
        files += (files.empty() ? "" : "; ") + f.path + " (" + std::to_string(f.bytes) + " bytes, fnv1a64 " + f.hash + ")";
    put(row, runColumnsDeclared().inputFiles, files);
}

RunScene sceneFor(const ExperimentPlan& plan, const RunConfig& run, Caches& caches, Row& row) {
    const std::string key = sceneKey(run);
    const std::shared_ptr<TriangleMesh>& full = fullScene(plan, run, caches);
    writeInputColumns(*full, row);
    const SceneInputColumns& c = sceneInputs();
    put(row, c.fullTriangles, full->triangles.size());
    put(row, c.triangles, full->triangles.size());
    validateSceneRange(*full);  // before the structure, the camera fit or Embree see it

    // Simplified: cached by scene and target, whatever the vertex bits.
    std::shared_ptr<TriangleMesh> simplified = full;
    bool sameTriangles = true;
    std::string tracedKey = key;
    if (run.has("scene.simplify_ratio") || run.has("scene.simplify_triangles")) {
        const bool exact = run.has("scene.simplify_triangles");
        const std::size_t target = std::max<std::size_t>(
            1, exact ? std::size_t(run.getInt("scene.simplify_triangles"))
                     : std::size_t(std::llround(run.getFloat("scene.simplify_ratio") * double(full->triangles.size()))));
        tracedKey += "|simplified to " + std::to_string(target) + (exact ? " exactly" : "");
        if (!caches.simplified.count(tracedKey)) {
            SimplifiedMesh result = simplifyMesh(*full, target, exact);
            caches.simplified[tracedKey] = {std::make_shared<TriangleMesh>(std::move(result.mesh)), result.ms, result.unchanged};
        }
        const SimplifiedScene& s = caches.simplified[tracedKey];
        put(row, c.simplifyMs, s.ms);
        if (!s.unchanged) simplified = s.mesh;  // else the same triangles, ids and all
        sameTriangles = s.unchanged;
    }
    // Snapped to the vertex lattice: cached by the above and the bits.
    std::shared_ptr<TriangleMesh> traced = simplified;
    const unsigned vertexBits = unsigned(run.getInt("intersection.vertex_bits"));
    if (vertexBits != 32) {
        tracedKey += "|" + std::to_string(vertexBits) + "-bit vertices";
        if (!caches.snapped.count(tracedKey))
            caches.snapped[tracedKey] = std::make_shared<TriangleMesh>(snapToLattice(*simplified, vertexBits));
        traced = caches.snapped[tracedKey];
        double snapError = 0.0;  // over the vertices of triangles
        for (const glm::uvec3& t : traced->triangles)
            for (int k = 0; k < 3; ++k)
                snapError = std::max(snapError, glm::length(glm::dvec3(traced->vertices[t[k]]) - glm::dvec3(simplified->vertices[t[k]])));
        put(row, c.latticeStep, traced->lattice.step);
        put(row, c.snapErrorMax, snapError);
    }
    const TriangleMesh& mesh = *traced;
    put(row, c.triangles, mesh.triangles.size());
    validateSceneRange(mesh);
    const std::size_t degenerate = mesh.degenerateCount();
    put(row, c.degenerate, degenerate);
    // What makes the scene differ from what its file describes, in the row and on the console.
    std::vector<std::string> warnings;
    if (degenerate)  // never hit by any method
        warnings.push_back(std::to_string(degenerate) + " of " + std::to_string(mesh.triangles.size()) +
                           " triangles are degenerate (zero area in float) and are never hit");
    if (mesh.elementsSkipped) warnings.push_back("skipped " + mesh.elementsSkippedWhat + " (not surfaces)");
    for (const std::string& w : warnings) addWarning(row, w);
    return {*full, mesh, sameTriangles, tracedKey};
}

PinholeCamera cameraFor(const RunConfig& run, const TriangleMesh& mesh) {
    const std::string source = run.getString("scene.source");
    PinholeCamera camera = fitCamera(mesh.bounds(), float(run.getFloat("camera.fov_deg")));
    if (source.rfind("procedural:", 0) == 0 && !run.has("camera.position") && !run.has("camera.look_at"))
        if (auto own = proceduralCamera(source.substr(11), camera.verticalFovDegrees)) {
            camera = *own;  // in the scene's own coordinates
            camera.position = sceneTransform(run, camera.position);
            camera.lookAt = sceneTransform(run, camera.lookAt);
        }
    if (run.has("camera.look_at")) camera.lookAt = sceneTransform(run, toVec3(run.getVec3("camera.look_at")));
    if (run.has("camera.position")) camera.position = sceneTransform(run, toVec3(run.getVec3("camera.position")));
    camera.up = toVec3(run.getVec3("camera.up"));
    return camera;
}

EmbreeReference& embreeFor(const RunConfig& run, const RunScene& scene, Caches& caches, Row& row) {
    const std::string embreeConfig = run.getString("baseline.embree_config");
    const std::string embreeKey = scene.tracedKey + "|" + embreeConfig;
    if (!caches.embree.count(embreeKey)) caches.embree[embreeKey] = std::make_shared<EmbreeReference>(scene.traced, embreeConfig);
    EmbreeReference& embree = *caches.embree[embreeKey];
    const EmbreeColumns& c = embreeColumnsDeclared();
    put(row, c.threads, embree.threads());
    put(row, c.isa, embree.isa());
    put(row, c.buildMs, embree.buildMs());
    return embree;
}

const ExactReference& exactReferenceFor(const RunConfig& run, const TriangleMesh& full, Caches& caches) {
    const std::string key = sceneKey(run);
    if (!caches.exact.count(key)) caches.exact[key] = std::make_shared<ExactReference>(full);
    return *caches.exact[key];
}

const ExactHits& traceExact(const RunConfig& run, const TriangleMesh& mesh, const std::vector<gpu::Ray>& rays,
                            Caches& caches) {
    const std::string scene = sceneKey(run);
    const std::uint64_t sampleSize = std::uint64_t(run.getInt("accuracy.exact_rays"));
    const std::string key = scene + "|" + std::to_string(fnv1a64({reinterpret_cast<const char*>(rays.data()),
                                                                    rays.size() * sizeof(gpu::Ray)})) +
                            "|" + std::to_string(sampleSize);
    if (!caches.exactHits.count(key))
        caches.exactHits[key] = std::make_shared<ExactHits>(exactReferenceFor(run, mesh, caches).trace(rays, sampleRays(rays.size(), sampleSize)));
    return *caches.exactHits[key];
}

}  // namespace rtbench
