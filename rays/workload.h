// What a run traces: the ray-type half of the method seam (rays.type), beside the structure and
// the strategy. A ray type makes the batch of rays a run measures, from the camera's rays and,
// for rays after the first hit, from the hits the structure's kernels find for those (their CPU
// reference, bit for bit the device's). Each lives in rays/<name>/ with its keys and
// columns; the runner knows none by name: rays/registry.cpp lists them.
#pragma once
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "device/vulkan_context.h"
#include "strategies/ray_batch.h"
#include "structures/structure.h"
#include "schema/column.h"
#include "schema/columns.h"
#include "schema/keys.h"
#include "scene/camera.h"
#include "scene/mesh.h"
#include "rays/shading.h"

namespace rtbench {

struct WorkloadInputs {
    const RunConfig& run;
    const TriangleMesh& scene;                // as the methods trace it (the structure's triangles)
    const std::vector<gpu::Ray>& cameraRays;  // one per pixel, row by row
    const Structure& structure;
    glm::vec3 cameraUp;
    // A point given in the scene's own coordinates, moved as the scene is (scene.scale, scene.translate).
    std::function<glm::vec3(glm::vec3)> toScene;
    // The frame cameraRays were made from (scene/camera.h): a ray type whose batch is those rays in
    // their order says so (RayBatch::camera), so that a strategy making camera rays itself (the
    // control) is handed the frame only then.
    std::shared_ptr<const CameraFrame> cameraFrame = nullptr;
};

// Rays traced before the batch, one generation of a path (a reflection iteration): each ray, its
// hit by the run's structure, and the ray of the generation before it was made from.
struct Generation {
    std::vector<gpu::Ray> rays;
    std::vector<gpu::HitRecord> hits;
    std::vector<std::uint32_t> parents;  // into the generation before (the first: the camera rays)
    std::vector<std::uint32_t> paths;    // each ray's path (rays/shading.h ShadedRays)
    std::vector<float> weights;          // each ray's weight (rays/shading.h ShadedRays)
};

// What the batch's image shows in the camera's pixels (harness/images.h makeBatchImage).
enum class BatchImage {
    Shadows,  // the camera hits, darkened where the batch's ray hit something (shadow rays)
    Hits,     // the batch rays' own hits, each at its pixel (what a mirror shows)
};

// The rays a run measures and where they come from.
struct Workload {
    RayBatch batch;
    // Rays after the first hit: each ray's pixel (the camera ray its path starts from), the camera
    // rays' hits, the generations traced between those and the batch, and each batch ray's
    // parent in the last of them (in the camera rays when there are none). All empty for the
    // camera rays themselves (ray i is pixel i).
    std::vector<std::uint32_t> pixels;
    std::vector<gpu::HitRecord> cameraHits;
    std::vector<Generation> between;
    std::vector<std::uint32_t> parents;
    std::vector<std::uint32_t> paths;  // each batch ray's path (rays/shading.h ShadedRays)
    std::vector<float> weights;        // each batch ray's weight (rays/shading.h ShadedRays)
    // The shading passes that made the generations after the camera rays: shading[g] made
    // generation g + 1 (between[g], the batch after the last) from generation g (0: the camera
    // rays). Run again on the device to check them (checkShadingOnDevice).
    std::vector<gpu::ShadingParams> shading;
    std::shared_ptr<const Surfaces> surfaces = std::make_shared<const Surfaces>();  // what the passes read
    std::uint64_t parentRays = 0, parentHits = 0;  // of the generation the batch was made from
    BatchImage image = BatchImage::Shadows;
    bool fromCamera() const { return pixels.empty() && cameraHits.empty(); }
    // Generation g as a shading pass reads it (0: the camera rays, `cameraRays`, and their hits).
    ShadingInput generation(std::size_t g, const std::vector<gpu::Ray>& cameraRays) const;
    // The ray batch ray `ray` descends from in generation g (0: the camera rays; between.size():
    // the batch itself).
    std::uint32_t ancestor(std::uint32_t ray, std::size_t g) const;
};

// The path `workload` traced to its batch, for a strategy that traces it whole on the device
// (StrategyType::TracePath): it points into `workload` and `cameraRays`, which must outlive it.
BatchPath batchPath(const Workload& workload, const std::vector<gpu::Ray>& cameraRays, const TriangleMesh& scene);

// Rays of `hits` that hit something.
std::uint64_t countHits(const std::vector<gpu::HitRecord>& hits);

// Paths from the camera rays through the shading passes `passes` over `surfaces`: each pass makes a
// generation from the one before, every generation but the last traced by the run's structure
// (closest hit), the last the batch, asked `query`. A pass that makes no ray throws rtbench::Error
// with noRays(pass, rays of the generation before, of which hit).
Workload followPaths(const WorkloadInputs& in, std::shared_ptr<const Surfaces> surfaces,
                     const std::vector<gpu::ShadingParams>& passes, std::uint32_t query,
                     const std::function<std::string(std::size_t, std::uint64_t, std::uint64_t)>& noRays);

// A ray type of generations' TYPE_parent_rays and TYPE_parent_hits (the generation the batch was
// made from), declared by the ray type, written by followGenerations.
struct ParentColumns {
    ParentColumns(const std::string& type, const std::string& raysHelp, const std::string& hitsHelp, int since)
        : rays(group.add<std::uint64_t>({type + "_parent_rays", ColumnKind::Exact, "rays", raysHelp, 0.0, false, {}, since})),
          hits(group.add<std::uint64_t>({type + "_parent_hits", ColumnKind::Exact, "rays", hitsHelp, 0.0, false, {}, since})) {}
    ColumnGroup group;
    Column<std::uint64_t> rays, hits;
};

// followPaths for a ray type of generations (reflection and refraction iterations, path bounces):
// closest hit; a pass that makes no ray is "rays.type = TYPE: no rays at KEY k: none of the N
// rays of NOUN k - 1 hit"; the image shows each ray's own hit; writes `parents`.
Workload followGenerations(const WorkloadInputs& in, Row& row, const std::vector<gpu::ShadingParams>& passes,
                           const std::string& type, const std::string& key, const std::string& noun, const ParentColumns& parents);

// Every shading pass of `workload` run again on the device (kernels/shading.comp) from the same
// rays and hits, its rays compared bit for bit with the CPU's. Writes shading_* columns to `row`;
// returns what differs ("" when nothing does), which fails the run.
// The columns checkShadingOnDevice writes.
const std::vector<ColumnSpec>& shadingColumns();

std::string checkShadingOnDevice(VulkanContext& vk, unsigned workgroupSize, const TriangleMesh& scene,
                                 const std::vector<gpu::Ray>& cameraRays, const Workload& workload, Row& row);

// How many rays a run of a ray type traces, as its plan knows them before tracing (`rtbench plan`).
enum class PlannedRays {
    OnePerCameraRay,  // exactly the camera rays
    AtMost,           // at most the camera rays times perCameraRayKey: the rays that continue from hits
    About,            // about the camera rays: rays branch by material and light, no bound before tracing
};

struct RayType {
    std::string name;  // the rays.type value
    std::string help;
    PlannedRays planned = PlannedRays::AtMost;
    std::string perCameraRayKey;  // the integer key that multiplies an AtMost bound ("" for one ray per camera ray)
    std::vector<KeySpec> keys;        // read only when rays.type is this name
    std::vector<ColumnSpec> columns;  // written only by its runs
    // Makes the batch; writes its own columns. Throws rtbench::Error for what it cannot make.
    Workload (*make)(const WorkloadInputs& inputs, Row& row);
};

// The seed key of a ray type of diffuse rays (`key`, e.g. "path.seed"): an integer of 32 bits,
// default 0, hashed with each ray's path and bounce (kernels/shading.glsl rtRandom).
KeySpec randomSeedKey(const std::string& key, const std::string& who);

// Marks every key and column of `type` as first written by results schema `schema`.
void setSince(RayType& type, int schema);

}  // namespace rtbench
