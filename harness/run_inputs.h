// What a run reads before it is timed, each made once per sweep and shared by the runs that need
// it (Caches): the device, the scene as its source gives it (what the exact reference traces) and
// as the methods trace it (simplified, snapped to a lattice), the camera, Embree's scene, the exact
// reference and its hits. The first stage of a run (harness/runner.cpp).
#pragma once
#include <array>
#include <chrono>
#include <map>
#include <memory>
#include <string>

#include "config.h"
#include "device/vulkan_context.h"
#include "embree_reference.h"
#include "exact_reference.h"
#include "scene/camera.h"
#include "scene/mesh.h"
#include "writers.h"

namespace rtbench {

// The scene columns sceneFor writes, and Embree's that embreeFor writes.
const std::vector<ColumnSpec>& sceneInputColumns();
const std::vector<ColumnSpec>& embreeColumns();

// A config's 3-vector as the float vector the scene and camera use.
glm::vec3 toVec3(const std::array<double, 3>& a);

// A scene simplified (scene.simplify_*).
struct SimplifiedScene {
    std::shared_ptr<TriangleMesh> mesh;
    double ms = 0.0;
    bool unchanged = false;  // the target was not below the count: the scene as it is
};

// What is cached across the runs of one plan (a sweep reuses scenes, devices, Embree scenes).
struct Caches {
    std::map<std::string, std::shared_ptr<TriangleMesh>> meshes;   // by sceneKey
    std::map<std::string, SimplifiedScene> simplified;             // by RunScene::tracedKey
    std::map<std::string, std::shared_ptr<TriangleMesh>> snapped;  // by RunScene::tracedKey
    std::map<std::string, std::shared_ptr<VulkanContext>> devices;
    std::map<std::string, std::shared_ptr<EmbreeReference>> embree;
    std::map<std::string, std::shared_ptr<ExactReference>> exact;  // by scene
    std::map<std::string, std::shared_ptr<ExactHits>> exactHits;   // by scene, rays and sample
    std::chrono::steady_clock::time_point started = std::chrono::steady_clock::now();  // samples' t_s origin
};

// The run's device (device.name, device.validation: the command line's -d and --validation are
// applied to the plan), opened once per sweep.
VulkanContext& deviceFor(const RunConfig& run, Caches& caches);

// The scene as a run sees it: its source moved by scene.scale and scene.translate, in float.
glm::vec3 sceneTransform(const RunConfig& run, glm::vec3 p);

// The cache key of a run's scene: its source and transform.
std::string sceneKey(const RunConfig& run);

// A run's scene twice: as its source describes it (what the exact reference traces) and as the
// methods trace it, simplified (scene.simplify_*) and snapped to a vertex lattice
// (intersection.vertex_bits); the same mesh when neither is asked for.
struct RunScene {
    const TriangleMesh& full;
    const TriangleMesh& traced;
    bool sameTriangles;     // traced triangle i is full triangle i (perhaps with moved vertices)
    std::string tracedKey;  // the traced mesh's cache key (Embree's scenes are cached by it too)
};

// The scene as its source describes it, moved; loaded once per sweep. Its `inputs` are the
// files read, as they were when read.
const std::shared_ptr<TriangleMesh>& fullScene(const ExperimentPlan& plan, const RunConfig& run, Caches& caches);

// What a row records of the files its scene was made from: part of the run's identity.
void writeInputColumns(const TriangleMesh& scene, Row& row);

// The run's scene, full and traced, with its input, triangle count, simplification and lattice
// columns and its warnings (degenerate triangles, skipped elements) written to `row`. Throws
// rtbench::Error for a scene that cannot be loaded or traced.
RunScene sceneFor(const ExperimentPlan& plan, const RunConfig& run, Caches& caches, Row& row);

// The run's camera: fitted to `mesh`'s box, or a procedural scene's own viewpoint, or as
// camera.position and camera.look_at give it, moved with the scene.
PinholeCamera cameraFor(const RunConfig& run, const TriangleMesh& mesh);

// Embree on the traced scene, built once per sweep for each scene and device config.
EmbreeReference& embreeFor(const RunConfig& run, const RunScene& scene, Caches& caches, Row& row);

// The exact reference of a scene, built once per scene.
const ExactReference& exactReferenceFor(const RunConfig& run, const TriangleMesh& full, Caches& caches);

// The exact first hits of the sampled rays, computed once per scene, rays and sample size.
const ExactHits& traceExact(const RunConfig& run, const TriangleMesh& mesh, const std::vector<gpu::Ray>& rays,
                            Caches& caches);

}  // namespace rtbench
