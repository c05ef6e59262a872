#include "runner.h"

#include <tbb/parallel_for.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <regex>
#include <set>
#include <fstream>
#include <sstream>
#include <thread>

#include "columns.h"
#include "device/gpu_buffers.h"
#include "device/vulkan_context.h"
#include "embree_reference.h"
#include "exact_reference.h"
#include "image_compare.h"
#include "images.h"
#include "methods/registry.h"
#include "methods/triangle_store.h"
#include "noise_guard.h"
#include "path_check.h"
#include "statistics.h"
#include "timing_rounds.h"
#include "output_folder.h"
#include "structures/camera.h"
#include "structures/error.h"
#include "structures/mesh_io.h"
#include "structures/procedural.h"
#include "structures/scene_description.h"
#include "structures/scene_limits.h"
#include "structures/simplify.h"
#include "version.h"
#include "workloads/registry.h"

namespace rtbench {
namespace fs = std::filesystem;

namespace {

// procedural:NAME, cgal:NAME, a scene description (*.toml) or a mesh file (structures/scene_description.h).
TriangleMesh loadScene(const std::string& source, const std::string& configDir) {
    return loadSceneSource(source, configDir);
}

glm::vec3 toVec3(const std::array<double, 3>& a) { return glm::vec3(float(a[0]), float(a[1]), float(a[2])); }

std::string num(double v, int significant = 6) { return formatNumber(v, significant); }

void writeArchitectureColumns(const ArchitectureMetrics& m, const Structure& structure, std::uint64_t rays, Row& row) {
    const WorkStats& w = m.work;
    structure.writeWorkColumns(w.cellsPerRayMean, w.cellsPerRayMax, m.bytes.cells, row);
    row["work_per_ray_mean"] = num(double(w.cellsTotal + w.trianglesTotal) / double(rays));
    row["triangles_per_ray_mean"] = num(w.trianglesPerRayMean);
    row["triangles_per_ray_max"] = std::to_string(w.trianglesPerRayMax);
    row["traversal_steps_per_ray_mean"] = num(double(w.stepsTotal) / double(rays));
    row["traversal_steps_per_ray_max"] = std::to_string(w.stepsPerRayMax);
    row["passes_total"] = std::to_string(m.passes);
    row["simd_efficiency"] = num(m.simdEfficiency);
    row["bytes_stencil"] = std::to_string(m.bytes.stencil);
    row["bytes_state"] = std::to_string(m.bytes.state);
    if (m.bytes.stack) row["bytes_stack"] = std::to_string(m.bytes.stack);
    row["bytes_triangle_list"] = std::to_string(m.bytes.triangleList);
    row["bytes_vertices"] = std::to_string(m.bytes.vertices);
    row["bytes_output"] = std::to_string(m.bytes.output);
    row["bytes_total"] = std::to_string(m.bytes.total());
    row["bytes_per_ray"] = num(double(m.bytes.total()) / double(rays));
}

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
VulkanContext& deviceFor(const RunConfig& run, Caches& caches) {
    const std::string deviceName = run.getString("device.name");
    const bool validation = run.getBool("device.validation");
    const std::string deviceKey = deviceName + (validation ? "+validation" : "");
    if (!caches.devices.count(deviceKey)) caches.devices[deviceKey] = std::make_shared<VulkanContext>(deviceName, validation);
    return *caches.devices[deviceKey];
}

// The scene as a run sees it: its source moved by scene.scale and scene.translate, in float.
glm::vec3 sceneTransform(const RunConfig& run, glm::vec3 p) {
    const float scale = float(run.getFloat("scene.scale"));
    const glm::vec3 translate = toVec3(run.getVec3("scene.translate"));
    return p * scale + translate;
}

// The cache key of a run's scene: its source and transform.
std::string sceneKey(const RunConfig& run) {
    return run.getString("scene.source") + "|" + formatValue(run.values.at("scene.scale")) + "|" +
           formatValue(run.values.at("scene.translate"));
}

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
const std::shared_ptr<TriangleMesh>& fullScene(const ExperimentPlan& plan, const RunConfig& run, Caches& caches) {
    const std::string key = sceneKey(run);
    if (!caches.meshes.count(key)) {
        TriangleMesh mesh = loadScene(run.getString("scene.source"), plan.configDir);
        for (glm::vec3& v : mesh.vertices) v = sceneTransform(run, v);
        caches.meshes[key] = std::make_shared<TriangleMesh>(std::move(mesh));
    }
    return caches.meshes[key];
}

// What a row records of the files its scene was made from: part of the run's identity.
void writeInputColumns(const TriangleMesh& scene, Row& row) {
    row["inputs_hash"] = inputsHash(scene.inputs);
    std::string files;
    for (const InputFile& f : scene.inputs)
        files += (files.empty() ? "" : "; ") + f.path + " (" + std::to_string(f.bytes) + " bytes, fnv1a64 " + f.hash + ")";
    row["input_files"] = files;
}

RunScene sceneFor(const ExperimentPlan& plan, const RunConfig& run, Caches& caches, Row& row) {
    const std::string key = sceneKey(run);
    const std::shared_ptr<TriangleMesh>& full = fullScene(plan, run, caches);
    writeInputColumns(*full, row);
    row["scene_full_triangles"] = row["scene_triangles"] = std::to_string(full->triangles.size());
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
        row["scene_simplify_ms"] = num(s.ms, 4);
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
        row["vertex_lattice_step"] = num(traced->lattice.step);
        row["vertex_snap_error_max"] = num(snapError, 4);
    }
    const TriangleMesh& mesh = *traced;
    row["scene_triangles"] = std::to_string(mesh.triangles.size());
    validateSceneRange(mesh);
    const std::size_t degenerate = mesh.degenerateCount();
    row["scene_degenerate"] = std::to_string(degenerate);
    // What makes the scene differ from what its file describes, in the row and on the console.
    std::vector<std::string> warnings;
    if (degenerate)  // never hit by any method
        warnings.push_back(std::to_string(degenerate) + " of " + std::to_string(mesh.triangles.size()) +
                           " triangles are degenerate (zero area in float) and are never hit");
    if (mesh.elementsSkipped) warnings.push_back("skipped " + mesh.elementsSkippedWhat + " (not surfaces)");
    for (const std::string& w : warnings) row["warnings"] += (row["warnings"].empty() ? "" : "; ") + w;
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

// Embree on the traced scene, built once per sweep for each scene and device config.
EmbreeReference& embreeFor(const RunConfig& run, const RunScene& scene, Caches& caches, Row& row) {
    const std::string embreeConfig = run.getString("baseline.embree_config");
    const std::string embreeKey = scene.tracedKey + "|" + embreeConfig;
    if (!caches.embree.count(embreeKey)) caches.embree[embreeKey] = std::make_shared<EmbreeReference>(scene.traced, embreeConfig);
    EmbreeReference& embree = *caches.embree[embreeKey];
    row["embree_threads"] = std::to_string(embree.threads());
    row["embree_isa"] = embree.isa();
    row["embree_build_ms"] = num(embree.buildMs(), 4);
    return embree;
}

// A timed series' statistics into <prefix>_ms_median, _min, _max, _mean, _std, _cv, _ci_low, _ci_high.
SampleStats writeTimingColumns(const std::string& prefix, const std::vector<double>& ms, Row& row) {
    const SampleStats s = summarize(ms);
    row[prefix + "_ms_median"] = num(s.median);
    row[prefix + "_ms_min"] = num(s.min);
    row[prefix + "_ms_max"] = num(s.max);
    row[prefix + "_ms_mean"] = num(s.mean);
    row[prefix + "_ms_std"] = num(s.stddev, 4);
    row[prefix + "_ms_cv"] = num(s.cv, 4);
    row[prefix + "_ms_ci_low"] = num(s.ciLow);
    row[prefix + "_ms_ci_high"] = num(s.ciHigh);
    return s;
}

// The methods a run's rounds time: the kernel (its KernelTimer) and Embree rtcIntersect1 and
// rtcIntersect16 (any hit: rtcOccluded1 and 16) on the same rays; the single rays' hits go to
// `embreeHits`.
std::vector<TimedMethod> timedMethods(KernelTimer& kernel, EmbreeReference& embree, const RayBatch& batch,
                                      std::vector<gpu::HitRecord>& embreeHits, std::vector<gpu::HitRecord>& scratch) {
    std::vector<TimedMethod> methods;
    methods.push_back({"kernel", [&kernel](int warmups, int repetitions) { return kernel.time(warmups, repetitions); }});
    for (EmbreeMode mode : {EmbreeMode::Intersect1, EmbreeMode::Intersect16})
        methods.push_back({mode == EmbreeMode::Intersect1 ? "embree1" : "embree16",
                           [&embree, &batch, &embreeHits, &scratch, mode](int warmups, int repetitions) {
                               TimedBatch timed;
                               for (int i = 0; i < warmups; ++i) timed.warmupMs += embree.trace(batch.rays, mode, scratch, batch.query);
                               for (int i = 0; i < repetitions; ++i)
                                   timed.ms.push_back(embree.trace(batch.rays, mode, mode == EmbreeMode::Intersect1 ? embreeHits : scratch,
                                                                   batch.query));
                               return timed;
                           }});
    return methods;
}

// A run's timing (harness/timing_rounds.h) into `row`: each method's statistics, the strategy's
// own series, the speed ratio with its interval, and the noise guard's reading of the window
// from `before` to now (harness/noise_guard.h).
void writeTimingResults(const RunConfig& run, const VulkanContext& vk, std::size_t rays, const RoundsResult& timed,
                        const CpuTimes& before, Row& row) {
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    const CpuTimes after = sampleCpuTimes();
    const SampleStats k = writeTimingColumns("kernel", timed.of("kernel"), row);
    row["kernel_mrays_s"] = num(k.median > 0 ? double(rays) / (k.median * 1e3) : 0.0);
    std::vector<std::string> noisy;
    const double noiseCv = run.getFloat("experiment.noise_cv");
    if (k.cv > noiseCv) noisy.push_back("kernel CV " + num(k.cv, 3));
    for (const char* m : {"embree1", "embree16"}) {
        const SampleStats e = writeTimingColumns(m, timed.of(m), row);
        row[std::string(m) + "_mrays_s"] = num(double(rays) / (e.median * 1e3));
        if (e.cv > noiseCv) noisy.push_back(std::string(m) + " CV " + num(e.cv, 3));
    }
    // The strategy's own series: the parts of a repetition, its host-controlled loops.
    for (const auto& [name, ms] : timed.series) {
        if (name.rfind("kernel_", 0) == 0) row["kernel_ms_" + name.substr(7)] = num(median(ms));
        else if (name != "kernel" && name != "embree1" && name != "embree16") row[name + "_ms_median"] = num(median(ms));
    }
    const double embreeMedian = median(timed.of("embree1"));
    row["speed_ratio_vs_embree1"] = num(k.median > 0 ? embreeMedian / k.median : 0.0, 4);
    const Interval ratio = bootstrapRatioOfMedians(timed.of("embree1"), timed.of("kernel"));
    row["speed_ratio_ci_low"] = num(ratio.low, 4);
    row["speed_ratio_ci_high"] = num(ratio.high, 4);
    row["timing_repetitions"] = std::to_string(timed.repetitions);
    row["timing_rounds"] = std::to_string(timed.rounds);
    row["timing_stop"] = timed.stop;
    row["timing_s"] = num(timed.seconds, 4);

    // The noise guard.
    const double other = otherCpuFraction(before, after, cores, double(::sysconf(_SC_CLK_TCK)));
    row["other_cpu_fraction"] = other < 0 ? "" : num(other, 3);
    const double load = loadAverage();
    row["load_average"] = load < 0 ? "" : num(load, 3);
    row["device_host_threads"] = std::to_string(deviceHostThreads(vk.info().type == "cpu", cores));
    if (!noisy.empty()) noisy.back() += " > experiment.noise_cv " + num(noiseCv, 3);
    if (other > run.getFloat("experiment.noise_other_cpu"))
        noisy.push_back("other processes took " + num(100 * other, 3) + "% of the machine's CPU time (> experiment.noise_other_cpu " +
                        num(run.getFloat("experiment.noise_other_cpu"), 3) + ")");
    for (const std::string& n : noisy) row["timing_warning"] += (row["timing_warning"].empty() ? "" : "; ") + n;
}

// The exact reference of a scene, built once per scene.
const ExactReference& exactReferenceFor(const RunConfig& run, const TriangleMesh& full, Caches& caches) {
    const std::string key = sceneKey(run);
    if (!caches.exact.count(key)) caches.exact[key] = std::make_shared<ExactReference>(full);
    return *caches.exact[key];
}

// The exact first hits of the sampled rays, computed once per scene, rays and sample size.
const ExactHits& traceExact(const RunConfig& run, const TriangleMesh& mesh, const std::vector<gpu::Ray>& rays,
                            Caches& caches, Row& row) {
    const std::string scene = sceneKey(run);
    const std::uint64_t sampleSize = std::uint64_t(run.getInt("accuracy.exact_rays"));
    const std::string key = scene + "|" + std::to_string(fnv1a64({reinterpret_cast<const char*>(rays.data()),
                                                                    rays.size() * sizeof(gpu::Ray)})) +
                            "|" + std::to_string(sampleSize);
    if (!caches.exactHits.count(key))
        caches.exactHits[key] = std::make_shared<ExactHits>(exactReferenceFor(run, mesh, caches).trace(rays, sampleRays(rays.size(), sampleSize)));
    const ExactHits& exact = *caches.exactHits[key];
    row["exact_rays"] = std::to_string(exact.rays.size());
    row["exact_ms"] = num(exact.ms, 4);
    return exact;
}

void writeExactColumns(const std::string& prefix, const ExactAccuracy& a, Row& row) {
    row[prefix + "false_misses"] = std::to_string(a.falseMisses);
    row[prefix + "false_hits"] = std::to_string(a.falseHits);
    if (a.primitivesCompared) row[prefix + "wrong_primitive"] = std::to_string(a.wrongPrimitive);
    row[prefix + "wrong_ppm"] = num(a.wrongPerMillion(), 6);
    if (!a.distancesCompared) return;
    row[prefix + "distance_error_mean"] = num(a.distanceErrorMean, 4);
    row[prefix + "distance_error_max"] = num(a.distanceErrorMax, 4);
}

// A shaded pixel differs from the exact render's when its 8-bit grey differs (by a level or more).
constexpr double kPixelDifferThreshold = 0.5 / 255.0;

// The batch's hits with the exact ones in place of the sampled rays': what the exact render is
// made from. In a tie the kernel's triangle is as right as the lowest-numbered one, and shades as it.
std::vector<gpu::HitRecord> exactInPlace(const std::vector<gpu::HitRecord>& hits, const ExactHits& exact, bool sameTriangles) {
    std::vector<gpu::HitRecord> out = hits;
    for (std::size_t i = 0; i < exact.rays.size(); ++i) {
        gpu::HitRecord& h = out[exact.rays[i]];
        const bool tie = sameTriangles && h.primitive != gpu::kNoHit && exact.isFirstHit(i, h.primitive);
        if (!tie) h.primitive = exact.hits[i].primitive;
    }
    return out;
}

// Image-level accuracy (harness/image_compare.h, idiff's measures): the 8-bit grey of the run's
// image (its hits) against the same image made with the exact hits of the sampled rays (the whole
// image when every ray is sampled, else the sampled rays' pixels as one row). `pixels`: the
// pixel of each batch ray (empty: ray i is pixel i).
void writeImageAccuracy(const HitImage& image, const HitImage& exactImage, const ExactHits& exact, std::size_t rays,
                        const std::vector<std::uint32_t>& pixels, Row& row) {
    const bool whole = exact.rays.size() == rays;
    std::vector<float> test, reference;
    auto addPixel = [&](std::size_t p) {
        test.push_back(float(pixelGrey(image.shade[p])) / 255.0f);
        reference.push_back(float(pixelGrey(exactImage.shade[p])) / 255.0f);
    };
    if (whole)
        for (std::size_t p = 0; p < image.shade.size(); ++p) addPixel(p);
    else
        for (std::uint32_t ray : exact.rays) addPixel(pixels.empty() ? ray : pixels[ray]);
    const ImageComparison c = compareImages(test, reference, whole ? image.width : unsigned(test.size()),
                                            whole ? image.height : 1u, kPixelDifferThreshold);
    row["image_psnr_db"] = num(c.psnr, 5);
    row["image_error_mean"] = num(c.meanError, 4);
    row["image_error_max"] = num(c.maxError, 4);
    row["image_pixels_differ"] = std::to_string(c.differing);
}

// A run from its scene to its timing: what its rounds and the rest of it need. It holds the
// run's device buffers (the strategy's timer) until the run is finished.
struct RunInProgress {
    const RunConfig* run = nullptr;
    VulkanContext* vk = nullptr;
    std::size_t messagesBefore = 0;
    CpuTimes started;  // the noise guard's window: from here to the end of the timing
    std::optional<RunScene> scene;
    unsigned width = 0, height = 0;
    std::vector<gpu::Ray> cameraRays;
    Workload workload;  // the batch the run measures
    std::string shadingMismatch;  // how the device's shading passes differ from the CPU's ("" if not)
    std::unique_ptr<Structure> structure;
    StrategyRun method;
    std::vector<gpu::HitRecord> embreeHits, scratch;  // written by the Embree batches
    std::unique_ptr<Rounds> rounds;
};

// One run, as the data flows: scene -> rays -> structure -> method (strategy on the device, checked
// against the structure's CPU reference) -> timing in rounds with Embree on the same rays -> the
// exact reference on a sample of them -> metrics -> images. Every value goes to `row`; a
// self-check that fails throws after the row is complete. prepareRun does all up to the timing;
// Rounds::runRound the timing, a round at a time; finishRun the rest.
std::unique_ptr<RunInProgress> prepareRun(const ExperimentPlan& plan, const RunConfig& run, Caches& caches, Row& row) {
    auto p = std::make_unique<RunInProgress>();
    p->run = &run;
    p->started = sampleCpuTimes();
    VulkanContext& vk = deviceFor(run, caches);
    p->vk = &vk;
    p->messagesBefore = vk.validationMessages().size();
    const StructureType& structureKind = structureType(run.getString("structure.type"));
    const StrategyType& strategy = strategyType(run.getString("strategy.type"));
    const RayType& rayKind = rayType(run.getString("rays.type"));

    // Scene and rays. Refuse before allocating: the per-ray buffers on the device (the largest
    // traversal state a structure keeps is checked again at upload) and the per-ray host data.
    const RunScene& scene = p->scene.emplace(sceneFor(plan, run, caches, row));
    const TriangleMesh& mesh = scene.traced;
    const PinholeCamera camera = cameraFor(run, scene.full);  // the same rays at every simplification
    for (int a = 0; a < 3; ++a) {
        const char axis[2] = {char('x' + a), 0};
        row[std::string("camera_eye_") + axis] = formatNumber(camera.position[a], 9);
        row[std::string("camera_target_") + axis] = formatNumber(camera.lookAt[a], 9);
    }
    p->width = unsigned(run.getInt("camera.width"));
    p->height = unsigned(run.getInt("camera.height"));
    refuseOversizedBuffers(vk.info(), rayBufferSizes(std::uint64_t(p->width) * p->height, strategy.perRayState ? 16 : 0));
    refuseOversizedRayStream(std::uint64_t(p->width) * p->height);
    p->cameraRays = generatePrimaryRays(camera, p->width, p->height);
    validateRays(p->cameraRays);

    // Structure: built for the camera rays (brute force refuses by their count, auto chooses by
    // its prediction for them).
    p->structure = structureKind.build(mesh, p->cameraRays, run, vk.info());
    Structure& structure = *p->structure;
    structure.setTriangleTest(run.getString("intersection.test") == "watertight" ? gpu::kTriangleTestWatertight
                                                                                 : gpu::kTriangleTestMollerTrumbore);

    // Workload: the batch of rays the run measures (rays.type), from the camera rays and, after
    // the first hit, from the structure's hits of them.
    const WorkloadInputs inputs{run, mesh, p->cameraRays, structure, camera.up,
                                [&run](glm::vec3 point) { return sceneTransform(run, point); }};
    p->workload = rayKind.make(inputs, row);
    if (const std::string query = run.getString("rays.query"); query != "own")
        p->workload.batch.query = query == "any" ? gpu::kQueryAny : gpu::kQueryClosest;
    const RayBatch& batch = p->workload.batch;
    const std::vector<gpu::Ray>& rays = batch.rays;
    validateRays(rays);
    p->shadingMismatch = checkShadingOnDevice(vk, unsigned(run.getInt("strategy.workgroup_size")), mesh, p->cameraRays,
                                              p->workload, row);
    row["rays"] = std::to_string(rays.size());
    row["query"] = queryName(batch.query);
    structure.writeColumns(row);
    row["structure_bytes"] = std::to_string(structure.memoryBytes);
    row["structure_bytes_per_triangle"] = num(double(structure.memoryBytes) / double(std::max<std::size_t>(mesh.triangles.size(), 1)));
    row["structure_build_ms"] = num(structure.buildMs, 4);
    row["predicted_work_per_ray"] = num(structure.predictedWork(rays) / double(rays.size()));

    // Method: the strategy runs the structure's kernels once, instrumented, and checks them
    // against its CPU reference.
    TimingOptions timing;
    timing.workgroupSize = unsigned(run.getInt("strategy.workgroup_size"));
    timing.warmups = timing.repetitions = 0;  // timed in rounds with Embree
    p->method = strategy.run(vk, structure, batch, run, timing, row);
    row["cpu_reference_mismatches"] = std::to_string(p->method.cpuMismatches);
    row["cpu_counts_match"] = p->method.countsMismatch.empty() ? "1" : "0";
    writeArchitectureColumns(p->method.metrics, structure, rays.size(), row);

    // Time: the kernel, uninstrumented, and Embree on the same rays, in rounds.
    EmbreeReference& embree = embreeFor(run, scene, caches, row);
    KernelTimer& kernel = *p->method.timer;
    p->rounds = std::make_unique<Rounds>(timedMethods(kernel, embree, batch, p->embreeHits, p->scratch),
                                         [&kernel] { return kernel.timeHostLoops(); }, roundsOptions(run), caches.started);
    return p;
}

void finishRun(RunInProgress& p, const std::string& folder, Caches& caches, Row& row, std::vector<TimingSample>& samples) {
    const RunConfig& run = *p.run;
    VulkanContext& vk = *p.vk;
    const RunScene& scene = *p.scene;
    const TriangleMesh& mesh = scene.traced;
    const Workload& workload = p.workload;
    const std::vector<gpu::Ray>& rays = workload.batch.rays;
    const std::uint32_t query = workload.batch.query;
    const StrategyRun& method = p.method;
    const unsigned width = p.width, height = p.height;
    const std::vector<gpu::HitRecord>& embreeHits = p.embreeHits;
    samples = p.rounds->result().samples;
    writeTimingResults(run, vk, rays.size(), p.rounds->result(), p.started, row);
    method.timer->checkHits();

    // The run's image from the batch's hits `hits`: the rays' own hits shaded on `shadedOn` (camera
    // rays, reflections, ...), or the camera hits changed by the batch's (shadow rays, ...); where
    // the hits differ from Embree's.
    const bool ownHits = workload.fromCamera() || workload.image == BatchImage::Hits;
    auto imageOf = [&](const std::vector<gpu::HitRecord>& hits, const TriangleMesh& shadedOn) {
        return ownHits ? makeHitImage(width, height, rays, shadedOn, hits, embreeHits, workload.pixels)
                       : makeBatchImage(width, height, p.cameraRays, workload.cameraHits, mesh, workload.pixels, hits,
                                        embreeHits);
    };
    const HitImage image = imageOf(method.hits, mesh);

    // Ground truth: the exact first hits of a sample of the rays on the full scene, for the kernel
    // and for Embree; the shaded pixels of those rays against the exact render.
    const ExactHits& exact = traceExact(run, scene.full, rays, caches, row);
    const ExactAccuracy kernelAccuracy = compareExact(method.hits, exact, scene.sameTriangles, query);
    row["exact_ties"] = std::to_string(kernelAccuracy.ties);
    writeExactColumns("exact_", kernelAccuracy, row);
    writeExactColumns("embree_exact_", compareExact(embreeHits, exact, scene.sameTriangles, query), row);
    // The exact render: the exact hits' own triangles of the full scene, or the camera hits (the
    // traced scene's, as the kernel's image) changed by the exact hits.
    writeImageAccuracy(image, imageOf(exactInPlace(method.hits, exact, scene.sameTriangles), scene.full), exact, rays.size(),
                       workload.pixels, row);
    if (!workload.fromCamera())  // the sampled rays' camera rays, judged too: did they leave from the exact scene's surface?
        row["exact_parent_wrong"] = std::to_string(pathsLeavingWrongHits(exactReferenceFor(run, scene.full, caches), p.cameraRays,
                                                                         workload, exact.rays, scene.sameTriangles));

    // Metrics: agreement with Embree.
    const Agreement a = compareHits(method.hits, embreeHits, query);
    row["hits"] = std::to_string(method.metrics.work.hits);
    row["hit_miss_agreement"] = num(a.hitMissAgreement, 8);
    row["hit_miss_mismatches"] = std::to_string(a.hitMissMismatches);
    if (a.primitivesCompared) {
        row["same_primitive_agreement"] = num(a.samePrimitiveAgreement, 8);
        row["rel_distance_error_mean"] = num(a.relDistanceErrorMean, 4);
        row["rel_distance_error_max"] = num(a.relDistanceErrorMax, 4);
        row["primitive_mismatches"] = std::to_string(a.primitiveMismatches);
    }

    // Writers: images, or the per-ray records to make them later.
    const std::string prefix = (fs::path(folder) / ("run-" + row["run"])).string();
    const bool wantImages = run.getBool("output.images");
    if (run.getBool("output.hit_records") || (wantImages && !imagesSupported())) writeHitRecords(prefix + ".hits", image, row["run"], row["config_hash"]);
    if (wantImages && imagesSupported()) writeImages(prefix, image, run.getBool("output.exr"));

    if (vk.validationMessages().size() != p.messagesBefore)
        throw Error("the Vulkan validation layer reported: " + vk.validationMessages()[p.messagesBefore]);
    // The row is complete; a kernel that disagrees with its CPU reference fails it all the same.
    if (!p.shadingMismatch.empty()) throw Error(p.shadingMismatch);
    if (method.truncatedRays) throw Error(method.truncatedWhy);
    if (method.cpuMismatches)
        throw Error("the kernel's hit records differ from the CPU reference's on " + std::to_string(method.cpuMismatches) +
                    " of " + std::to_string(rays.size()) + " rays");
    if (!method.countsMismatch.empty())
        throw Error("the kernel's " + method.countsMismatch + " from the CPU reference's");
    if (method.branchingMismatches)
        throw Error("the multipass hit records differ from the branching caster's on " +
                    std::to_string(method.branchingMismatches) + " of " + std::to_string(rays.size()) + " rays");
}

// One run, whole: prepared, timed round after round, finished.
void executeRun(const ExperimentPlan& plan, const RunConfig& run, const std::string& folder, Caches& caches, Row& row,
                std::vector<TimingSample>& samples) {
    const std::unique_ptr<RunInProgress> p = prepareRun(plan, run, caches, row);
    while (!p->rounds->done()) p->rounds->runRound();
    finishRun(*p, folder, caches, row, samples);
}

// What is needed to re-run and to judge the experiment: written when the sweep starts, with every
// device it uses already opened (complete: false), and once more at its end (complete: true). The
// runs done are runs.csv's rows, so `rtbench check` works on an interrupted sweep, and a run's
// bookkeeping does not grow with the plan.
Json contextJson(const ExperimentPlan& plan, const RunnerOptions& options, const Caches& caches,
                 const std::string& startedUtc, bool complete) {
    Json j;
    j["command"] = options.commandLine;
    j["config_path"] = plan.configPath;
    j["config_text"] = plan.configText;
    j["config_dir"] = plan.configDir;
    j["overrides"] = Json::object();  // the command line's -d, --validation, --embree-config
    for (const auto& [key, value] : plan.overrides) j["overrides"][key] = value;
    j["shard"] = options.shardCount > 1 ? std::to_string(options.shardIndex) + "/" + std::to_string(options.shardCount) : "";
    j["schema_version"] = kSchemaVersion;
    j["git_commit"] = gitCommit();
    j["date_utc"] = startedUtc;
    j["complete"] = complete;
    j["host"] = hostName();
    j["cpu"] = cpuModel();
    j["cpu_threads"] = std::thread::hardware_concurrency();
    j["embree_version"] = EmbreeReference::version();
    j["images"] = imagesSupported() ? "OpenImageIO" : "hit records only";
    j["devices"] = Json::array();
    for (const auto& [key, vk] : caches.devices) {
        const DeviceInfo& d = vk->info();
        j["devices"].push_back({{"name", d.name}, {"driver", d.driver}, {"api", d.apiVersion}, {"type", d.type},
                                {"subgroup_size", d.subgroupSize}, {"max_storage_buffer_range", d.maxStorageBufferRange},
                                {"timestamp_period_ns", d.timestampPeriodNs}});
    }
    j["plan"] = Json::array();
    for (const RunConfig& run : plan.runs)
        j["plan"].push_back({{"run", runNumber(run)}, {"config_hash", run.hash()}, {"label", run.label()}});
    return j;
}

// A run's identity beyond its parameters (config_hash): the commit of the binary, the device it
// ran on and the contents of the files its scene was made from. A row of an earlier invocation
// stands for a run of this plan only when all of them are equal.
std::string identity(const Row& row) {
    auto get = [&](const char* column) {
        const auto it = row.find(column);
        return it == row.end() ? std::string() : it->second;
    };
    return get("run") + "|" + get("config_hash") + "|" + get("git_commit") + "|" + get("device") + "|" + get("driver") +
           "|" + get("cpu") + "|" + get("inputs_hash");
}

// "<folder>/superseded-<UTC time>[-k]-": the prefix of what one invocation sets aside (rows,
// samples, the context they were run under, their per-run files), names merge and resume never
// read, and the start of no existing file's name.
std::string supersededPrefix(const std::string& folder) {
    std::string stamp = utcNow();
    stamp.erase(std::remove(stamp.begin(), stamp.end(), ':'), stamp.end());
    stamp.erase(std::remove(stamp.begin(), stamp.end(), '-'), stamp.end());
    std::set<std::string> names;  // every name in the folder: a prefix no file has yet
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(folder, ec)) names.insert(entry.path().filename().string());
    for (int k = 0;; ++k) {
        const std::string name = "superseded-" + stamp + (k ? "-" + std::to_string(k) : "") + "-";
        const auto after = names.lower_bound(name);
        if (after == names.end() || after->rfind(name, 0) != 0) return (fs::path(folder) / name).string();
    }
}

// Sets aside rows of an earlier invocation that a resume does not keep: the rows, their timing
// samples (and samples of runs whose row was never written), the context they were recorded under
// (the old context.json, before this invocation replaces it), and each row's per-run files
// (run-NNN.hits, -shaded.png, -diff.png), which would else sit beside a new row of the same run
// number. Returns the prefix of their names.
std::string setAside(const std::string& folder, const std::string& csvName, const std::string& contextPath,
                     const std::vector<std::string>& columns, const std::vector<Row>& rows,
                     const std::string& samplesName, const std::vector<Row>& samples) {
    const std::string prefix = supersededPrefix(folder);
    if (!rows.empty()) writeCsv(prefix + csvName, columns, rows);
    if (!samples.empty()) writeCsv(prefix + samplesName, sampleColumns(), samples);
    std::error_code ec;
    if (fs::is_regular_file(fs::symlink_status(contextPath, ec)))
        writeFileAtomically(prefix + fs::path(contextPath).filename().string(),
                            readInputFile(contextPath, kMaxResultsFileBytes, "JSON file"));
    for (const Row& row : rows)
        for (const char* suffix : {".hits", "-shaded.png", "-diff.png"}) {
            const fs::path file = fs::path(folder) / ("run-" + row.at("run") + suffix);
            if (fs::is_regular_file(fs::symlink_status(file, ec)))
                fs::rename(file, prefix + file.filename().string(), ec);
        }
    return prefix;
}

// The text of a CSV this invocation resumes from. A last row without its line end was cut while
// written (a crash, power lost): it is set aside as it is, and the rows before it stand.
std::string readResumable(const std::string& folder, const std::string& path, const std::string& name) {
    std::string text = readInputFile(path, kMaxResultsFileBytes, "CSV file");
    if (text.empty() || text.back() == '\n') return text;
    const std::size_t end = text.rfind('\n');
    const std::string prefix = supersededPrefix(folder);
    writeFileAtomically(prefix + name + ".cut-row", end == std::string::npos ? text : text.substr(end + 1));
    text.resize(end == std::string::npos ? 0 : end + 1);
    std::cerr << "[rtbench] " << path << ": its last row was cut while written; set aside in " << prefix << name
              << ".cut-row, and run again\n";
    return text;
}

// Every scene.source the runs name exists (structures/scene_description.h checkSceneSource);
// else an error naming the config, the key, the source and its runs.
void checkSceneSources(const ExperimentPlan& plan, const std::vector<const RunConfig*>& runs) {
    std::map<std::string, std::vector<std::string>> bySource;
    for (const RunConfig* run : runs) bySource[run->getString("scene.source")].push_back(runNumber(*run));
    for (const auto& [source, numbers] : bySource) {
        try {
            checkSceneSource(source, plan.configDir);
        } catch (const Error& e) {
            std::string which;
            for (std::size_t i = 0; i < numbers.size() && i < 6; ++i) which += (i ? ", " : "") + numbers[i];
            if (numbers.size() > 6) which += ", ... (" + std::to_string(numbers.size()) + " runs)";
            throw Error(plan.configPath + ": key 'scene.source' = \"" + source + "\" (run " + which + "): " + e.what() +
                        "; nothing was run");
        }
    }
}

// A run's timing samples as samples.csv rows.
std::vector<Row> sampleRows(const Row& row, const std::vector<TimingSample>& samples) {
    std::vector<Row> rows;
    for (const TimingSample& s : samples)
        rows.push_back({{"run", row.at("run")}, {"config_hash", row.at("config_hash")}, {"method", s.method},
                        {"round", std::to_string(s.round)}, {"repetition", std::to_string(s.repetition)},
                        {"ms", formatNumber(s.ms, 9)}, {"t_s", formatNumber(s.t, 9)}});
    return rows;
}

}  // namespace

std::string runNumber(const RunConfig& run) {
    char index[16];
    std::snprintf(index, sizeof index, "%03zu", run.index);
    return index;
}

std::string summaryTable(const std::vector<Row>& rows) {
    // Speed (with the ratio's 95% interval) and the exact accuracy; the swept parameters last, whole.
    std::ostringstream out;
    auto get = [](const Row& r, const char* key) {
        auto it = r.find(key);
        return it == r.end() || it->second.empty() ? std::string("-") : it->second;
    };
    out << std::left << std::setw(5) << "run" << std::right << std::setw(13) << "kernel Mr/s" << std::setw(14)
        << "Embree1 Mr/s" << std::setw(10) << "ratio" << std::setw(22) << "ratio 95% interval" << std::setw(12)
        << "wrong ppm" << std::setw(9) << "status" << "  " << std::left << "parameters (wrong ppm: against the exact reference)\n";
    for (const Row& r : rows) {
        const std::string interval =
            get(r, "speed_ratio_ci_low") == "-" ? "-" : "[" + get(r, "speed_ratio_ci_low") + ", " + get(r, "speed_ratio_ci_high") + "]";
        out << std::left << std::setw(5) << get(r, "run") << std::right << std::setw(13) << get(r, "kernel_mrays_s")
            << std::setw(14) << get(r, "embree1_mrays_s") << std::setw(10) << get(r, "speed_ratio_vs_embree1") << std::setw(22)
            << interval << std::setw(12) << get(r, "exact_wrong_ppm") << std::setw(9) << get(r, "status") << "  " << std::left
            << get(r, "label") << (get(r, "timing_warning") == "-" ? "" : " [timing_warning]") << "\n";
    }
    for (const Row& r : rows)
        if (get(r, "status") == "failed") out << "run " << get(r, "run") << " failed: " << get(r, "error") << "\n";
    return out.str();
}

namespace {
std::string shardSuffix(const RunnerOptions& options) {
    if (options.shardCount <= 1) return "";
    return ".shard-" + std::to_string(options.shardIndex) + "-of-" + std::to_string(options.shardCount);
}
}  // namespace

std::string runsFileName(const RunnerOptions& options) { return "runs" + shardSuffix(options) + ".csv"; }
std::string contextFileName(const RunnerOptions& options) { return "context" + shardSuffix(options) + ".json"; }
std::string samplesFileName(const RunnerOptions& options) { return "samples" + shardSuffix(options) + ".csv"; }

ExperimentResult runExperiment(const ExperimentPlan& plan, const RunnerOptions& options) {
    ExperimentResult result;
    if (options.shardCount == 0 || options.shardIndex >= options.shardCount)
        throw Error("--shard " + std::to_string(options.shardIndex) + "/" + std::to_string(options.shardCount) +
                    ": expected i/N with 0 <= i < N");
    if (plan.runs.empty()) throw Error(plan.configPath + ": the plan has no runs");
    const RunConfig& first = plan.runs.front();
    const std::string output = options.outputOverride.empty() ? first.getString("experiment.output") : options.outputOverride;
    result.folder = experimentFolder(output, first.getString("experiment.name"));
    // What would fail every run fails the command before any folder is made: a device that is not
    // there (its name and driver are part of each run's identity) or a scene source that is not.
    std::vector<const RunConfig*> mine;
    for (const RunConfig& run : plan.runs)
        if (run.index % options.shardCount == options.shardIndex &&
            (options.onlyRuns.empty() || options.onlyRuns.count(runNumber(run))))
            mine.push_back(&run);
    Caches caches;
    for (const RunConfig* run : mine) deviceFor(*run, caches);
    checkSceneSources(plan, mine);
    std::error_code ec;
    if (fs::is_symlink(fs::symlink_status(result.folder, ec))) refuseSymlinks(result.folder);
    fs::create_directories(result.folder, ec);
    if (ec || !fs::is_directory(result.folder))
        throw Error(result.folder + ": cannot create the results folder" + (ec ? ": " + ec.message() : std::string()));
    // Everything below writes the folder: one writer of each file, checked before any run.
    const std::unique_ptr<OutputFolderLock> lock =
        options.shardCount > 1 ? std::make_unique<OutputFolderLock>(result.folder, shardSuffix(options).substr(1))
                               : std::make_unique<OutputFolderLock>(result.folder);
    refuseSymlinks(result.folder);
    const std::string csvName = runsFileName(options);
    const std::string csvPath = (fs::path(result.folder) / csvName).string();
    const std::string contextPath = (fs::path(result.folder) / contextFileName(options)).string();
    const std::string samplesName = samplesFileName(options);
    const std::string samplesPath = (fs::path(result.folder) / samplesName).string();
    checkWritableFile(csvPath);
    checkWritableFile(contextPath);
    checkWritableFile(samplesPath);
    const std::vector<std::string> columns = runColumns();

    // Rows of an earlier invocation that can stand: ok, and the same run in every input.
    std::vector<Row> earlierRows, earlierSamples;
    // An earlier runs CSV (and its samples): read to resume from, or, unreadable with --force,
    // moved aside whole.
    auto readEarlier = [&](const std::string& path, const std::string& name, auto parse) {
        std::vector<Row> rows;
        if (!fs::exists(fs::symlink_status(path, ec))) return rows;
        try {
            rows = parse(readResumable(result.folder, path, name), path);
        } catch (const Error& e) {
            if (!options.force)
                throw Error(std::string(e.what()) + "; cannot resume from it (--force re-runs every run and replaces it)");
            rows.clear();  // --force replaces it; the unreadable file is kept aside
            const std::string aside = supersededPrefix(result.folder) + name;
            fs::rename(path, aside, ec);
            if (ec) throw Error(path + ": cannot move the unreadable file aside: " + ec.message());
            std::cerr << "[rtbench] " << path << " could not be read (" << e.what() << "); kept as " << aside << "\n";
        }
        return rows;
    };
    earlierRows = readEarlier(csvPath, csvName, [](const std::string& text, const std::string& path) { return parseRunsCsv(text, path); });
    earlierSamples = readEarlier(samplesPath, samplesName, parseSamplesCsv);
    std::map<std::string, const Row*> earlier;  // by identity
    std::set<std::string> earlierRuns;           // "run|config_hash" of those
    if (!options.force)
        for (const Row& row : earlierRows)
            if (row.at("status") == "ok") {
                earlier[identity(row)] = &row;
                earlierRuns.insert(row.at("run") + "|" + row.at("config_hash"));
            }

    const std::string started = utcNow();
    // Each run's row as it will be written: its parameters and identity (the scene's inputs are
    // hashed as loaded, so only runs with an earlier row to match load their scene here).
    std::vector<Row> rows(mine.size());
    std::vector<bool> kept(mine.size(), false);
    std::set<const Row*> keptEarlier;
    std::map<std::string, std::string> inputsNow;  // run -> inputs_hash, of runs with an earlier ok row
    for (std::size_t k = 0; k < mine.size(); ++k) {
        const RunConfig& run = *mine[k];
        Row& row = rows[k];
        for (const auto& [key, value] : run.values)
            for (const auto& [column, cell] : keyCells(keySpec(key), value)) row[column] = cell;
        row["run"] = runNumber(run);
        row["label"] = run.label();
        row["sweep"] = run.sweep;
        row["config_hash"] = run.hash();
        row["git_commit"] = gitCommit();
        const VulkanContext& vk = deviceFor(run, caches);
        row["device"] = vk.info().name;
        row["driver"] = vk.info().driver;
        row["cpu"] = cpuModel();
        if (!earlierRuns.count(row["run"] + "|" + row["config_hash"])) continue;
        Row withInputs = row;
        try {
            writeInputColumns(*fullScene(plan, run, caches), withInputs);
        } catch (const std::exception&) {
            continue;  // the scene no longer loads: the run is run again, and says why
        }
        inputsNow[row["run"]] = withInputs["inputs_hash"];
        const auto previous = earlier.find(identity(withInputs));
        if (previous == earlier.end()) continue;
        row = *previous->second;
        row["label"] = run.label();  // the label names the swept keys of this plan
        kept[k] = true;
        keptEarlier.insert(previous->second);
    }
    // Earlier rows that do not stand are never lost: they are set aside in a file of their own.
    std::vector<Row> superseded;
    std::set<std::string> planned;
    for (const RunConfig& run : plan.runs) planned.insert(runNumber(run) + "|" + run.hash());
    std::map<std::string, const Row*> planRow;  // run -> this invocation's row of it
    for (const Row& row : rows) planRow[row.at("run")] = &row;
    // Why each earlier row is not kept, first reason first.
    std::map<std::string, std::size_t> why;
    for (const Row& row : earlierRows)
        if (!keptEarlier.count(&row)) {
            superseded.push_back(row);
            const auto now = planRow.find(row.at("run"));
            auto differs = [&](const char* column) { return now->second->at(column) != (row.count(column) ? row.at(column) : ""); };
            const char* reason = !planned.count(row.at("run") + "|" + row.at("config_hash")) ? "no longer in the plan"
                                 : row.at("status") != "ok"                                   ? "failed"
                                 : options.force                                               ? "--force"
                                 : now == planRow.end()                                        ? "another shard's"
                                 : differs("git_commit")                                       ? "another commit"
                                 : differs("device") || differs("driver")                      ? "another device or driver"
                                 : differs("cpu")                                              ? "another CPU"
                                 : !inputsNow.count(row.at("run"))                             ? "a scene that no longer loads"
                                                                                               : "other input files";
            ++why[reason];
        }
    // The samples of kept rows stand with them; the rest (superseded rows', and those of a run
    // interrupted before its row was written) are set aside.
    std::set<std::string> keptRuns;
    for (const Row* row : keptEarlier) keptRuns.insert(row->at("run") + "|" + row->at("config_hash"));
    std::vector<Row> keptSamples, supersededSamples;
    for (Row& sample : earlierSamples)
        (keptRuns.count(sample.at("run") + "|" + sample.at("config_hash")) ? keptSamples : supersededSamples).push_back(std::move(sample));
    if (superseded.empty() && !supersededSamples.empty()) {
        const std::string aside = setAside(result.folder, csvName, contextPath, columns, {}, samplesName, supersededSamples);
        std::cerr << "[rtbench] " << supersededSamples.size() << " timing sample(s) of " << samplesPath
                  << " belong to no row (a run interrupted before its row was written); they are saved in " << aside
                  << samplesName << "\n";
    }
    if (!superseded.empty()) {
        const std::string aside =
            setAside(result.folder, csvName, contextPath, columns, superseded, samplesName, supersededSamples) + csvName;
        std::string notInPlanRuns;
        for (const Row& row : superseded)
            if (!planned.count(row.at("run") + "|" + row.at("config_hash")))
                notInPlanRuns += (notInPlanRuns.empty() ? "" : ", ") + row.at("run") + " (" + row.at("label") + ")";
        std::string reasons;
        for (const auto& [reason, count] : why)
            if (count) reasons += (reasons.empty() ? "" : ", ") + std::to_string(count) + " " + reason;
        std::cerr << "[rtbench] " << superseded.size() << " row(s) of " << csvPath << " are not kept (" << reasons << ")"
                  << (notInPlanRuns.empty() ? "" : "; no longer in the plan: " + notInPlanRuns) << "; they are saved in "
                  << aside << "\n";
    }
    if (!earlierRows.empty() && !options.quiet) {
        const std::size_t keptCount = std::size_t(std::count(kept.begin(), kept.end(), true));
        std::cout << "[rtbench] resuming " << csvPath << ": " << keptCount << " row(s) kept, " << mine.size() - keptCount
                  << " run(s) to run, " << superseded.size() << " earlier row(s) set aside\n";
    }

    // The bookkeeping: context.json once now and once at the end; runs.csv written once with the
    // kept rows, then one appended row per run.
    writeJson(contextPath, contextJson(plan, options, caches, started, false));
    writeFileAtomically((fs::path(result.folder) / "columns.csv").string(), columnsCsv());
    {
        std::vector<Row> keptRows;
        for (std::size_t k = 0; k < mine.size(); ++k)
            if (kept[k]) keptRows.push_back(rows[k]);
        writeCsv(csvPath, columns, keptRows);
        writeCsv(samplesPath, sampleColumns(), keptSamples);  // the kept runs' samples first
    }
    if (!options.quiet)
        std::cout << "[rtbench] " << plan.configPath << ": " << mine.size() << " run" << (mine.size() == 1 ? "" : "s")
                  << (options.shardCount > 1 ? " (shard " + std::to_string(options.shardIndex) + "/" +
                                                   std::to_string(options.shardCount) + " of " +
                                                   std::to_string(plan.runs.size()) + ")"
                                             : std::string())
                  << " -> " << result.folder << "/" << csvName << "\n";
    const auto experimentStart = std::chrono::steady_clock::now();
    using Clock = std::chrono::steady_clock;
    auto since = [](Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); };
    double executedSeconds = 0.0;
    int executed = 0;
    // A run's row is complete (ok, or failed with `error`): said on the console, then its samples
    // and its row appended. The samples come first: an interrupt between them leaves samples
    // without a row, which a resume sets aside, never a row without its samples.
    auto record = [&](std::size_t k, const std::string& error, double seconds, const std::vector<TimingSample>& samples) {
        Row& row = rows[k];
        row["status"] = error.empty() ? "ok" : "failed";
        if (!error.empty()) {
            row["error"] = error;
            ++result.failed;
        }
        executedSeconds += seconds;
        ++executed;
        row["wall_s"] = formatNumber(seconds, 4);
        if (!options.quiet) {
            if (row["status"] == "ok")
                std::cout << " " << row["kernel_mrays_s"] << " Mrays/s (Embree " << row["embree1_mrays_s"]
                          << "), hit/miss agreement " << row["hit_miss_agreement"] << ", " << row["wall_s"] << " s\n";
            else
                std::cout << " FAILED: " << row["error"] << "\n";
        }
        if (!row["warnings"].empty()) std::cerr << "[rtbench] run " << row["run"] << " warning: " << row["warnings"] << "\n";
        if (!row["timing_warning"].empty())
            std::cerr << "[rtbench] run " << row["run"] << " timing warning: " << row["timing_warning"]
                      << " (not a timing of record)\n";
        appendCsvRows(samplesPath, sampleColumns(), sampleRows(row, samples));
        appendCsvRow(csvPath, columns, row);  // an interrupt loses nothing done
    };
    // Progress: runs done, elapsed, and an estimate for the rest from the runs executed so far.
    auto progress = [&](const char* what, std::size_t k) {
        if (options.quiet) return;
        std::cout << "[" << what << " " << k + 1 << "/" << mine.size() << ", " << std::fixed << std::setprecision(0)
                  << since(experimentStart) << " s";
        if (executed > 0 && std::string(what) == "run") std::cout << ", ~" << executedSeconds / executed * double(mine.size() - k) << " s left";
        std::cout << "] " << mine[k]->label() << " ..." << std::defaultfloat << std::flush;
    };
    for (std::size_t k = 0; k < mine.size(); ++k)
        if (kept[k]) {
            ++result.reused;
            if (!options.quiet) std::cout << "[run " << k + 1 << "/" << mine.size() << "] " << mine[k]->label() << ": done before, kept\n";
        }
    if (first.getString("experiment.order") != "interleaved") {
        for (std::size_t k = 0; k < mine.size(); ++k) {
            if (kept[k]) continue;
            progress("run", k);
            const auto start = Clock::now();
            std::vector<TimingSample> samples;
            std::string error;
            try {
                executeRun(plan, *mine[k], result.folder, caches, rows[k], samples);
            } catch (const std::exception& e) {
                error = e.what();
            }
            record(k, error, since(start), samples);
        }
    } else {
        // Interleaved (experiment.order): every run is prepared (its instrumented run and checks),
        // then timed one round at a time across the sweep, round r of every run before round r + 1
        // of any, so runs compared in one table were timed under the same conditions; then each is
        // finished. Every prepared run keeps its device buffers until then.
        std::vector<std::unique_ptr<RunInProgress>> running(mine.size());
        std::vector<double> seconds(mine.size(), 0.0);
        for (std::size_t k = 0; k < mine.size(); ++k) {
            if (kept[k]) continue;
            progress("prepare", k);
            const auto start = Clock::now();
            try {
                running[k] = prepareRun(plan, *mine[k], caches, rows[k]);
                if (!options.quiet) std::cout << " prepared\n";
            } catch (const std::exception& e) {
                record(k, e.what(), since(start), {});
            }
            seconds[k] += since(start);
        }
        for (int round = 0;; ++round) {
            std::size_t timing = 0;
            for (std::size_t k = 0; k < mine.size(); ++k) {
                if (!running[k] || running[k]->rounds->done()) continue;
                ++timing;
                const auto start = Clock::now();
                try {
                    running[k]->rounds->runRound();
                } catch (const std::exception& e) {
                    running[k].reset();  // its buffers go now
                    if (!options.quiet) std::cout << "[round " << round + 1 << "] " << mine[k]->label() << ":";
                    record(k, e.what(), seconds[k] + since(start), {});
                }
                seconds[k] += since(start);
            }
            if (!timing) break;
            if (!options.quiet)
                std::cout << "[round " << round + 1 << ", " << std::fixed << std::setprecision(0) << since(experimentStart)
                          << " s] " << timing << " run(s) timed\n" << std::defaultfloat;
        }
        for (std::size_t k = 0; k < mine.size(); ++k) {
            if (!running[k]) continue;
            progress("finish", k);
            const auto start = Clock::now();
            std::vector<TimingSample> samples;
            std::string error;
            try {
                finishRun(*running[k], result.folder, caches, rows[k], samples);
            } catch (const std::exception& e) {
                error = e.what();
            }
            running[k].reset();
            record(k, error, seconds[k] + since(start), samples);
        }
    }
    result.rows = rows;
    writeCsv(csvPath, columns, result.rows);  // in plan order
    writeJson(contextPath, contextJson(plan, options, caches, started, true));
    return result;
}

namespace {

// One shard's files as merge reads them.
struct ShardFiles {
    fs::path csv, context;
    Json json;
};

std::string contextField(const Json& context, const fs::path& path, const char* key) {
    const auto it = context.find(key);
    if (it == context.end()) throw Error(path.string() + ": no \"" + key + "\" field");
    return it->is_string() ? it->get<std::string>() : it->dump();
}

}  // namespace

std::vector<Row> mergeShards(const std::string& folder) {
    std::error_code ec;
    if (!fs::is_directory(folder, ec)) throw Error(folder + ": not a results folder");
    refuseSymlinks(folder);  // before the lock file is made
    const OutputFolderLock lock(folder);  // no shard is running
    // runs.shard-<i>-of-<n>.csv with its context.shard-<i>-of-<n>.json.
    std::map<std::string, ShardFiles> shards;
    const std::regex csvName(R"(runs\.(shard-[0-9]+-of-[0-9]+)\.csv)"), contextName(R"(context\.(shard-[0-9]+-of-[0-9]+)\.json)");
    for (const auto& entry : fs::directory_iterator(folder)) {
        const std::string name = entry.path().filename().string();
        std::smatch m;
        if (std::regex_match(name, m, csvName)) shards[m[1]].csv = entry.path();
        if (std::regex_match(name, m, contextName)) shards[m[1]].context = entry.path();
    }
    if (shards.empty()) throw Error(folder + ": no runs.shard-*.csv files to merge");
    std::set<std::string> counts;
    for (auto& [shard, files] : shards) {
        if (files.csv.empty()) throw Error(folder + ": " + files.context.filename().string() + " has no runs." + shard + ".csv");
        if (files.context.empty()) throw Error(folder + ": " + files.csv.filename().string() + " has no context." + shard + ".json");
        files.json = readJson(files.context.string());
        counts.insert(shard.substr(shard.rfind("-of-") + 4));
    }
    if (counts.size() > 1) throw Error(folder + ": shards of different splits (of-" + *counts.begin() + " and of-" + *counts.rbegin() + ")");
    // The shards must be parts of one experiment: the same config text, overrides, plan and commit.
    const ShardFiles& reference = shards.begin()->second;
    for (const auto& [shard, files] : shards)
        for (const char* key : {"config_text", "overrides", "plan", "git_commit"}) {
            const std::string a = contextField(reference.json, reference.context, key),
                              b = contextField(files.json, files.context, key);
            if (a != b) {
                const std::string what = std::string(key) == "git_commit" ? "were run at other commits (" + a + " and " + b + ")"
                                         : std::string(key) == "plan" ? "have other plans"
                                         : std::string(key) == "overrides" ? "were run with other command-line overrides (" + a + " and " + b + ")"
                                                                           : "were run from other config texts: the plans differ";
                throw Error(folder + ": " + reference.context.filename().string() + " and " +
                            files.context.filename().string() + " " + what + "; they cannot be merged");
            }
        }
    std::map<std::string, std::string> planned;  // run -> config_hash
    try {
        for (const Json& run : reference.json.at("plan"))
            planned[run.at("run").get<std::string>()] = run.at("config_hash").get<std::string>();
    } catch (const Json::exception& e) {
        throw Error(reference.context.string() + ": no valid \"plan\" list: " + e.what());
    }
    if (planned.empty()) throw Error(reference.context.string() + ": its plan lists no runs");
    const std::string commit = contextField(reference.json, reference.context, "git_commit");
    std::map<std::string, Row> byRun;
    bool complete = true;
    for (const auto& [shard, files] : shards) {
        const auto it = files.json.find("complete");
        if (it == files.json.end() || !it->is_boolean()) throw Error(files.context.string() + ": no boolean \"complete\" field");
        complete = complete && it->get<bool>();
        for (const Row& row : readRunsCsv(files.csv.string())) {
            const std::string& run = row.at("run");
            const std::string name = files.csv.filename().string() + ": run " + run + " (" + row.at("label") + ")";
            if (!planned.count(run) || planned[run] != row.at("config_hash")) throw Error(folder + ": " + name + " is not in the plan");
            if (row.at("git_commit") != commit) throw Error(folder + ": " + name + " was run at commit " + row.at("git_commit") + ", the shards at " + commit);
            if (!byRun.emplace(run, row).second) throw Error(folder + ": " + name + " appears in more than one shard");
        }
    }
    for (const auto& [run, hash] : planned)
        if (!byRun.count(run)) throw Error(folder + ": run " + run + " is missing from the shards");
    // One device, and one content of each scene's files, across the shards.
    std::map<std::string, const Row*> byScene;
    const Row* firstRow = &byRun.begin()->second;
    for (const auto& [run, row] : byRun) {
        const auto machine = [](const Row& r) { return r.at("device") + " (" + r.at("driver") + ") with " + r.at("cpu"); };
        if (machine(row) != machine(*firstRow))
            throw Error(folder + ": run " + firstRow->at("run") + " ran on " + machine(*firstRow) + " and run " + run + " on " +
                        machine(row) + "; a merged runs.csv holds one device and CPU (Embree's speed depends on it)");
        if (row.at("inputs_hash").empty()) continue;  // the scene did not load: the row says why
        const std::string scene = row.at("scene_source");
        const auto [it, inserted] = byScene.emplace(scene, &row);
        if (!inserted && it->second->at("inputs_hash") != row.at("inputs_hash"))
            throw Error(folder + ": runs " + it->second->at("run") + " and " + run + " read other contents of scene.source '" + scene +
                        "' (" + it->second->at("input_files") + " against " + row.at("input_files") + ")");
    }
    std::vector<Row> merged;
    for (const auto& [run, row] : byRun) merged.push_back(row);
    // Merging again is fine; replacing other results is not.
    auto refuseToReplace = [&](const std::string& path, auto read, const std::vector<Row>& merge) {
        checkWritableFile(path);
        if (!fs::exists(fs::symlink_status(path, ec))) return;
        std::vector<Row> existing;
        try {
            existing = read(path);
        } catch (const Error& e) {
            throw Error(path + ": exists and is not the merge of these shards (" + e.what() + "); move it away first");
        }
        if (existing != merge)
            throw Error(path + ": exists and differs from the merge of these shards (" + std::to_string(existing.size()) +
                        " rows against " + std::to_string(merge.size()) + "); move it away first");
    };
    const std::string csvPath = (fs::path(folder) / "runs.csv").string();
    refuseToReplace(csvPath, [](const std::string& path) { return readRunsCsv(path); }, merged);
    // The shards' timing samples, of the merged rows only, in run order.
    std::vector<Row> samples;
    std::size_t withSamples = 0;
    for (const auto& [shard, files] : shards) {
        const fs::path path = fs::path(folder) / ("samples." + shard + ".csv");
        if (!fs::exists(fs::symlink_status(path, ec))) continue;
        ++withSamples;
        for (Row& sample : readSamplesCsv(path.string())) {
            const auto row = byRun.find(sample.at("run"));
            if (row == byRun.end() || row->second.at("config_hash") != sample.at("config_hash"))
                throw Error(path.string() + ": a sample of run " + sample.at("run") + " (config_hash " + sample.at("config_hash") +
                            ") that no shard's row has");
            samples.push_back(std::move(sample));
        }
    }
    if (withSamples && withSamples != shards.size())
        throw Error(folder + ": " + std::to_string(withSamples) + " of " + std::to_string(shards.size()) +
                    " shards have a samples file; a shard's samples.shard-*.csv is missing");
    // Every ok row's repetitions are there: as many kernel, Embree 1 and Embree 16 samples as it
    // says it took.
    if (withSamples) {
        std::map<std::string, std::size_t> count;  // run|method
        for (const Row& sample : samples) ++count[sample.at("run") + "|" + sample.at("method")];
        for (const auto& [run, row] : byRun) {
            const auto reps = row.find("timing_repetitions");
            if (row.at("status") != "ok" || reps == row.end() || reps->second.empty()) continue;
            for (const char* method : {"kernel", "embree1", "embree16"})
                if (std::to_string(count[run + "|" + method]) != reps->second)
                    throw Error(folder + ": run " + run + " took " + reps->second + " repetitions of each method, the shards' samples hold " +
                                std::to_string(count[run + "|" + method]) + " of " + method);
        }
    }
    std::stable_sort(samples.begin(), samples.end(), [](const Row& a, const Row& b) { return a.at("run") < b.at("run"); });
    const std::string samplesPath = (fs::path(folder) / "samples.csv").string();
    if (withSamples)
        refuseToReplace(samplesPath, readSamplesCsv, samples);
    else
        checkWritableFile(samplesPath);
    writeCsv(csvPath, runColumns(), merged);
    if (withSamples) writeCsv(samplesPath, sampleColumns(), samples);
    Json context = reference.json;
    context["complete"] = complete;
    context["shard"] = "";
    writeJson((fs::path(folder) / "context.json").string(), context);
    return merged;
}

}  // namespace rtbench
