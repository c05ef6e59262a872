#include "run_pipeline.h"

#include <chrono>
#include <filesystem>
#include <variant>

#include "core/error.h"
#include "core/overloaded.h"
#include "device/gpu_buffers.h"
#include "device/vulkan_context.h"
#include "harness/build_rounds.h"
#include "harness/embree_reference.h"
#include "harness/exact_reference.h"
#include "harness/images.h"
#include "harness/run_metrics.h"
#include "harness/path_check.h"
#include "harness/run_verdict.h"
#include "methods/registry.h"
#include "rays/primary/tile_order.h"
#include "schema/column.h"
#include "schema/warnings.h"
#include "scene/camera.h"
#include "rays/registry.h"
#include "strategies/ray_batch.h"

namespace rtbench {
namespace fs = std::filesystem;

namespace {

// The columns this file's stages write, declared once, here.
struct PipelineColumns {
    using K = ColumnKind;
    using U64 = std::uint64_t;
    // The batch of rays the run measures.
    ColumnGroup batch;
    Column<U64> rays = batch.add<U64>({"rays", K::Exact, "rays", "rays traced: the batch of rays.type the run measures"});
    Column<std::string> query = batch.add<std::string>(
        {"query", K::Exact, "", "what the rays ask: closest (the nearest hit) or any (whether anything is hit in [tMin, tMax): the walk ends at its first hit; Embree's rtcOccluded)", 0.0, false, {}, 7});
    // The camera the rays came from, and the structure.
    ColumnGroup cameraAndStructure;
    std::array<Column<double>, 3> eye = {eyeColumn("x"), eyeColumn("y"), eyeColumn("z")};
    std::array<Column<double>, 3> target = {targetColumn("x"), targetColumn("y"), targetColumn("z")};
    Column<U64> structureBytes = cameraAndStructure.add<U64>(
        {"structure_bytes", K::Exact, "bytes", "device memory of the structure (its buffers, triangle vertices included; the driver's: its two levels' storage)"});
    Column<double> structureBytesPerTriangle = cameraAndStructure.add<double>(
        {"structure_bytes_per_triangle", K::Exact, "bytes", "structure_bytes / scene_triangles"});
    Column<double> structureBuildMs = cameraAndStructure.add<double>(
        {"structure_build_ms", K::Timing, "ms", "CPU build time of the structure (the driver's: its builds on the device, GPU timestamps)"}, 4);
    Column<double> predictedWork = cameraAndStructure.add<double>(
        {"predicted_work_per_ray", K::Exact, "operations",
         "cost model: cells or nodes visited + triangles tested per ray, predicted from the structure alone (SAH-style, no early termination)"});
    // Agreement with Embree on the same rays (a second view of accuracy: depends on Embree's
    // floating-point path, so compared within a tolerance).
    ColumnGroup agreement;
    Column<U64> hits = agreement.add<U64>({"hits", K::Exact, "rays", "rays the kernel hit"});
    Column<double> hitMissAgreement = agreement.add<double>(
        {"hit_miss_agreement", K::Reference, "fraction", "rays whose hit/miss equals Embree's", 1e-4}, 8);
    Column<double> samePrimitiveAgreement = agreement.add<double>(
        {"same_primitive_agreement", K::Reference, "fraction", "rays both hit on the same triangle", 1e-4}, 8);
    Column<double> relDistanceErrorMean = agreement.add<double>(
        {"rel_distance_error_mean", K::Reference, "", "|t - t_Embree| / t_Embree, mean over rays both hit", 1e-6}, 4);
    Column<double> relDistanceErrorMax = agreement.add<double>(
        {"rel_distance_error_max", K::Reference, "", "|t - t_Embree| / t_Embree, max", 1e-6}, 4);
    Column<U64> hitMissMismatches = agreement.add<U64>(
        {"hit_miss_mismatches", K::Reference, "rays", "rays where one hit and the other missed", 1e-4, true});
    Column<U64> primitiveMismatches = agreement.add<U64>(
        {"primitive_mismatches", K::Reference, "rays", "rays both hit on different triangles", 1e-4, true});
    // The rays the exact reference judges (accuracy.exact_rays).
    ColumnGroup exactSample;
    Column<U64> exactRays = exactSample.add<U64>({"exact_rays", K::Exact, "rays", "rays traced by the exact reference (accuracy.exact_rays)"});
    Column<U64> exactTies = exactSample.add<U64>(
        {"exact_ties", K::Exact, "rays", "of those, rays whose exact first hit is shared by several triangles (each is correct)"});
    Column<double> exactMs = exactSample.add<double>({"exact_ms", K::Timing, "ms", "wall time of the exact reference on those rays"}, 4);
    Column<U64> exactParentWrong = exactSample.add<U64>(
        {"exact_parent_wrong", K::Exact, "rays",
         "rays after the first hit: of the exact_rays, those with a ray earlier on their path (the camera ray, an earlier reflection) "
         "whose hit is not an exact first hit (they leave from another surface than the exact scene's; still judged as the rays they are)",
         0.0, false, {}, 7});
    // Rays Embree traced beside the kernel.
    Column<U64> embreeRays = Column<U64>(
        {"embree_rays", K::Exact, "rays",
         "rays Embree traced per repetition: the batch's, or beside a strategy that traces the whole path (wavefront, "
         "path_megakernel) every generation's, as the kernel did", 0.0, false, {}, 19});
    // Self-checks of the method against the CPU reference (a mismatch fails the run).
    ColumnGroup selfCheck;
    Column<U64> cpuMismatches = selfCheck.add<U64>(
        {"cpu_reference_mismatches", K::Exact, "rays",
         "rays whose GPU hit record differs from the CPU reference's (empty for the driver's ray query: another's arithmetic, judged by the exact reference)"});
    Column<int> cpuCountsMatch = selfCheck.add<int>(
        {"cpu_counts_match", K::Exact, "",
         "1 when pass and lane counts equal the CPU reference's (lane counts only on a device whose subgroups run "
         "in lock step; empty for branching elsewhere, where they are not compared)"});

private:
    Column<double> eyeColumn(const std::string& axis) {
        return cameraAndStructure.add<double>(
            {"camera_eye_" + axis, K::Exact, "scene units",
             "the camera the rays came from (fitted to the scene, or as given, moved with it): eye position, " + axis, 0.0, false, {}, 5}, 9);
    }
    Column<double> targetColumn(const std::string& axis) {
        return cameraAndStructure.add<double>(
            {"camera_target_" + axis, K::Exact, "scene units", "the camera's point looked at, " + axis, 0.0, false, {}, 5}, 9);
    }
};

const PipelineColumns& pipelineColumns() {
    static const PipelineColumns columns;
    return columns;
}

// The methods a run's rounds time: the kernel (its KernelTimer) and Embree rtcIntersect1 and
// rtcIntersect16 (any hit: rtcOccluded1 and 16) on the same rays (every generation of `path`, for
// a strategy that traces it whole); the single rays' hits of the batch go to `embreeHits`, the
// rays each repetition traced to `embreeRays`.
std::vector<TimedMethod> timedMethods(KernelTimer& kernel, EmbreeReference& embree, const RayBatch& batch,
                                      const BatchPath* path, std::vector<gpu::HitRecord>& embreeHits,
                                      std::vector<gpu::HitRecord>& scratch, std::uint64_t& embreeRays) {
    std::vector<TimedMethod> methods;
    methods.push_back({"kernel", [&kernel](int warmups, int repetitions) { return kernel.time(warmups, repetitions); }});
    for (EmbreeMode mode : {EmbreeMode::Intersect1, EmbreeMode::Intersect16})
        methods.push_back({mode == EmbreeMode::Intersect1 ? "embree1" : "embree16",
                           [&embree, &batch, path, &embreeHits, &scratch, &embreeRays, mode](int warmups, int repetitions) {
                               // What the kernel traced: the batch, or every generation of its path,
                               // those before the batch as closest-hit queries.
                               auto trace = [&](std::vector<gpu::HitRecord>& hits) {
                                   double ms = 0.0;
                                   embreeRays = batch.rays.size();
                                   if (path)
                                       for (std::size_t g = 0; g + 1 < path->generations.size(); ++g) {
                                           ms += embree.trace(*path->generations[g].rays, mode, scratch, gpu::kQueryClosest);
                                           embreeRays += path->generations[g].rays->size();
                                       }
                                   return ms + embree.trace(batch.rays, mode, hits, batch.query);
                               };
                               TimedBatch timed;
                               for (int i = 0; i < warmups; ++i) timed.warmupMs += trace(scratch);
                               for (int i = 0; i < repetitions; ++i)
                                   timed.ms.push_back(trace(mode == EmbreeMode::Intersect1 ? embreeHits : scratch));
                               return timed;
                           }});
    return methods;
}

// A record naming a triangle the scene lacks (a kernel gone wrong) is no hit to judge, shade or
// shoot rays from: the run fails here, before anything reads the scene at that index.
void refuseForeignTriangles(const std::vector<gpu::HitRecord>& hits, std::size_t triangles) {
    for (std::size_t i = 0; i < hits.size(); ++i)
        if (hits[i].primitive != gpu::kNoHit && hits[i].primitive >= triangles)
            throw Error("the kernel's record of ray " + std::to_string(i) + " names triangle " +
                        std::to_string(hits[i].primitive) + ", but the scene has " + std::to_string(triangles));
}

// Scene and camera rays: the run's scene (simplified, snapped as the run asks) and its camera's
// rays; returns the camera. Refuses before allocating: the per-ray buffers on the device, together
// (a binding holds one batch: the strategies trace a longer stream in batches, and check the
// batches' structure copies and the largest traversal state again), and the per-ray host data.
PinholeCamera prepareSceneAndRays(RunInProgress& p, const ExperimentPlan& plan, const StrategyType& strategy, Caches& caches,
                                  Row& row) {
    const RunConfig& run = *p.run;
    const VulkanContext& vk = *p.vk;
    const RunScene& scene = p.scene.emplace(sceneFor(plan, run, caches, row));
    const PinholeCamera camera = cameraFor(run, scene.full);  // the same rays at every simplification
    for (int a = 0; a < 3; ++a) {
        put(row, pipelineColumns().eye[std::size_t(a)], camera.position[a]);
        put(row, pipelineColumns().target[std::size_t(a)], camera.lookAt[a]);
    }
    p.width = unsigned(run.getInt("camera.width"));
    p.height = unsigned(run.getInt("camera.height"));
    const std::uint64_t streamRays = std::uint64_t(p.width) * p.height;
    std::vector<BufferSize> perRay = rayBufferSizes(streamRays);
    if (strategy.ownBytesPerRay)
        perRay.push_back({strategy.name + "'s own per-ray buffers", streamRays * strategy.ownBytesPerRay});
    refuseOversizedTotal(vk.info(), perRay);
    refuseOversizedRayStream(std::uint64_t(p.width) * p.height);
    p.cameraFrame = std::make_shared<const CameraFrame>(cameraFrame(camera, p.width, p.height));
    p.cameraRays = generatePrimaryRays(*p.cameraFrame);
    validateRays(p.cameraRays);
    return camera;
}

// The structure, built for the camera rays (brute force refuses by their count, auto chooses by its
// prediction for them), with the run's triangle arithmetic, and put on the device.
void buildStructure(RunInProgress& p, const StructureType& kind, const TriangleMesh& mesh) {
    const RunConfig& run = *p.run;
    VulkanContext& vk = *p.vk;
    p.structure = kind.build(mesh, p.cameraRays, run, vk.info());
    Structure& structure = *p.structure;
    structure.setArithmetic({run.getString("intersection.test") == "watertight" ? gpu::kTriangleTestWatertight
                                                                                : gpu::kTriangleTestMollerTrumbore,
                             run.getString("intersection.division") == "integer" ? gpu::kDivisionInteger
                                                                                 : gpu::kDivisionDouble});
    structure.buildOnDevice(vk);
}

// The batch of rays the run measures (rays.type), from the camera rays and, after the first hit,
// from the structure's hits of them; its columns and the structure's.
void makeWorkload(RunInProgress& p, const RayType& rayKind, const PinholeCamera& camera,
                  Row& row) {
    const RunConfig& run = *p.run;
    VulkanContext& vk = *p.vk;
    const TriangleMesh& mesh = p.scene->traced;
    Structure& structure = *p.structure;
    const WorkloadInputs inputs{run, mesh, p.cameraRays, structure, camera.up,
                                [&run](glm::vec3 point) { return sceneTransform(run, point); }, p.cameraFrame};
    p.workload = rayKind.make(inputs, row);
    if (const std::string query = run.getString("rays.query"); query != "own")
        p.workload.batch.query = queryOfName(query);
    const RayBatch& batch = p.workload.batch;
    const std::vector<gpu::Ray>& rays = batch.rays;
    validateRays(rays);
    p.shadingMismatch = checkShadingOnDevice(vk, unsigned(run.getInt("strategy.workgroup_size")), mesh, p.cameraRays,
                                              p.workload, row);
    const PipelineColumns& c = pipelineColumns();
    put(row, c.rays, rays.size());
    put(row, c.query, queryName(batch.query));
    structure.writeColumns(row);
    put(row, c.structureBytes, structure.memoryBytes);
    put(row, c.structureBytesPerTriangle, double(structure.memoryBytes) / double(std::max<std::size_t>(mesh.triangles.size(), 1)));
    put(row, c.structureBuildMs, structure.buildMs);
    const double predicted = structure.predictedWork(rays);
    put(row, c.predictedWork, predicted < 0 ? std::nullopt : std::optional<double>(predicted / double(rays.size())));
}

// The method: the strategy runs the structure's kernels once, instrumented, and checks them against
// its CPU reference; their hits in the batch's order, the architecture's columns.
void runMethod(RunInProgress& p, const StrategyType& strategy, Row& row) {
    const RunConfig& run = *p.run;
    VulkanContext& vk = *p.vk;
    const TriangleMesh& mesh = p.scene->traced;
    Structure& structure = *p.structure;
    const RayBatch& batch = p.workload.batch;
    const std::vector<gpu::Ray>& rays = batch.rays;
    TimingOptions timing;
    timing.workgroupSize = unsigned(run.getInt("strategy.workgroup_size"));
    timing.warmups = timing.repetitions = 0;  // timed in rounds with Embree
    const unsigned tile = run.has("camera.tile") ? unsigned(run.getInt("camera.tile")) : 0u;  // camera rays only
    auto traceBatch = [&](StrategyType::TraceBatch trace) {
        // camera.tile (Purcell §5.3): the method traces the rays tile by tile; its records come
        // back in the batch's order. Embree traces them row by row.
        const std::vector<std::uint32_t> order = tileOrder(p.width, p.height, tile);
        if (order.empty()) return trace(vk, structure, batch, run, timing, row);
        p.tiled = inOrder(batch, order);
        StrategyRun method = trace(vk, structure, p.tiled, run, timing, row);
        method.hits = inBatchOrder(method.hits, order);
        return method;
    };
    auto tracePath = [&](StrategyType::TracePath trace) {
        if (tile) throw Error("camera.tile: strategy.type = " + strategy.name + " traces the camera rays in the order they are made");
        p.path = batchPath(p.workload, p.cameraRays, mesh);  // the generations before the batch and the passes
        return trace(vk, structure, batch, *p.path, run, timing, row);
    };
    p.method = std::visit(Overloaded{traceBatch, tracePath}, strategy.trace);
    const PipelineColumns& c = pipelineColumns();
    put(row, c.cpuMismatches, p.method.cpuCompared ? std::optional<std::uint64_t>(p.method.cpuMismatches) : std::nullopt);
    refuseForeignTriangles(p.method.hits, mesh.triangles.size());
    put(row, c.cpuCountsMatch, p.method.countsCompared ? std::optional<int>(p.method.countsMismatch.empty()) : std::nullopt);
    writeArchitectureColumns(p.method.metrics, structure, rays.size(), row);
}

// The run's image from the batch's hits: the rays' own hits shaded on `shadedOn` (camera rays,
// reflections, ...), or the camera hits changed by the batch's (shadow rays, ...); where the hits
// differ from Embree's.
struct RunImage {
    const RunInProgress& p;
    bool ownHits() const { return p.workload.fromCamera() || p.workload.image == BatchImage::Hits; }
    HitImage operator()(const std::vector<gpu::HitRecord>& hits, const TriangleMesh& shadedOn) const {
        const Workload& w = p.workload;
        return ownHits() ? makeHitImage(p.width, p.height, w.batch.rays, shadedOn, hits, p.embreeHits, w.pixels)
                         : makeBatchImage(p.width, p.height, p.cameraRays, w.cameraHits, p.scene->traced, w.pixels, hits,
                                          p.embreeHits);
    }
};

// Ground truth: the exact first hits of a sample of the rays on the full scene, for the kernel and
// for Embree; the shaded pixels of those rays against the exact render.
void judgeAgainstExact(const RunInProgress& p, const RunImage& imageOf, const HitImage& image, Caches& caches, Row& row) {
    const RunConfig& run = *p.run;
    const RunScene& scene = *p.scene;
    const TriangleMesh& mesh = scene.traced;
    const Workload& workload = p.workload;
    const std::vector<gpu::Ray>& rays = workload.batch.rays;
    const std::uint32_t query = workload.batch.query;
    const StrategyRun& method = p.method;
    const unsigned width = p.width, height = p.height;
    const bool ownHits = imageOf.ownHits();
    const ExactHits& exact = traceExact(run, scene.full, rays, caches);
    const ExactAccuracy kernelAccuracy = compareExact(method.hits, exact, scene.sameTriangles, query);
    const PipelineColumns& c = pipelineColumns();
    put(row, c.exactRays, exact.rays.size());
    put(row, c.exactMs, exact.ms);
    put(row, c.exactTies, kernelAccuracy.ties);
    writeExactColumns(false, kernelAccuracy, row);
    writeExactColumns(true, compareExact(p.embreeHits, exact, scene.sameTriangles, query), row);
    // The exact render: the exact hits' own triangles of the full scene, or the camera hits (the
    // traced scene's, as the kernel's image) changed by the exact hits. When only some rays are
    // sampled, each sampled ray's own value (as if it alone made its pixel), one row of them.
    const std::vector<gpu::HitRecord> exactHits = exactInPlace(method.hits, exact, scene.sameTriangles, query);
    if (exact.rays.size() == rays.size()) {
        writeImageAccuracy(image.shade, imageOf(exactHits, scene.full).shade, width, height, row);
    } else {
        auto rayShade = [&](std::uint32_t r, const gpu::HitRecord& hit, const TriangleMesh& shadedOn) {
            if (ownHits) return shadeHit(shadedOn, hit.primitive, rays[r]);
            const std::uint32_t pixel = workload.pixels[r];
            return litShade(shadeHit(mesh, workload.cameraHits[pixel].primitive, p.cameraRays[pixel]),
                            hit.primitive == gpu::kNoHit ? 1.0f : 0.0f);
        };
        std::vector<float> shades, exactShades;
        for (std::uint32_t r : exact.rays) {
            shades.push_back(rayShade(r, method.hits[r], mesh));
            exactShades.push_back(rayShade(r, exactHits[r], scene.full));
        }
        writeImageAccuracy(shades, exactShades, unsigned(shades.size()), 1u, row);
    }
    if (!workload.fromCamera())  // the sampled rays' camera rays, judged too: did they leave from the exact scene's surface?
        put(row, c.exactParentWrong, pathsLeavingWrongHits(exactReferenceFor(run, scene.full, caches), p.cameraRays, workload,
                                                           exact.rays, scene.sameTriangles));
}

// Agreement with Embree on the same rays.
void writeAgreement(const RunInProgress& p, Row& row) {
    const StrategyRun& method = p.method;
    const Agreement a = compareHits(method.hits, p.embreeHits, p.workload.batch.query);
    const PipelineColumns& c = pipelineColumns();
    put(row, c.hits, method.metrics.work.hits);
    put(row, c.hitMissAgreement, a.hitMissAgreement);
    put(row, c.hitMissMismatches, a.hitMissMismatches);
    if (a.primitivesCompared) {
        put(row, c.samePrimitiveAgreement, a.samePrimitiveAgreement);
        put(row, c.relDistanceErrorMean, a.relDistanceErrorMean);
        put(row, c.relDistanceErrorMax, a.relDistanceErrorMax);
        put(row, c.primitiveMismatches, a.primitiveMismatches);
    }
}

// The run's files: its images, or the per-ray records to make them later.
void writeRunFiles(const RunConfig& run, const FolderIdentity& folder, const HitImage& image, Row& row) {
    folder.check();  // still the folder the sweep opened
    const std::string prefix = (fs::path(folder.path()) / ("run-" + row["run"])).string();
    const bool wantImages = run.getBool("output.images");
    if (run.getBool("output.hit_records") || (wantImages && !imagesSupported())) writeHitRecords(prefix + ".hits", image, row["run"], row["config_hash"]);
    if (wantImages && imagesSupported()) writeImages(prefix, image, run.getBool("output.exr"));
    if (wantImages && !imagesSupported() && run.getBool("output.exr"))
        addWarning(row, "output.exr: built without OpenImageIO, no EXR written (rtbench images makes PNGs only)");
}

// experiment.build_rounds: the structure, built again as this run built it, against Embree's BVH.
void timeBuilds(RunInProgress& p, const StructureType& kind, const EmbreeReference& embree, const Caches& caches, Row& row) {
    const RunConfig& run = *p.run;
    VulkanContext& vk = *p.vk;
    const TriangleMesh& mesh = p.scene->traced;
    auto buildStructure = [&] {
        const std::unique_ptr<Structure> again = kind.build(mesh, p.cameraRays, run, vk.info());
        again->buildOnDevice(vk);
        return again->buildMs;
    };
    const double start = std::chrono::duration<double>(std::chrono::steady_clock::now() - caches.started).count();
    const BuildRounds rounds = timeBuildRounds(int(run.getInt("experiment.build_rounds")), buildStructure, [&] { return embree.timeBuild(mesh); });
    writeBuildRoundColumns(rounds, row);
    p.buildSamples = buildRoundSamples(rounds, start);
}

}  // namespace

const std::vector<ColumnSpec>& batchColumns() { return pipelineColumns().batch.specs(); }
const std::vector<ColumnSpec>& cameraAndStructureColumns() { return pipelineColumns().cameraAndStructure.specs(); }
const std::vector<ColumnSpec>& agreementColumns() { return pipelineColumns().agreement.specs(); }
const std::vector<ColumnSpec>& exactSampleColumns() { return pipelineColumns().exactSample.specs(); }
const ColumnSpec& embreeRaysColumn() { return pipelineColumns().embreeRays.spec(); }
const std::vector<ColumnSpec>& selfCheckColumns() { return pipelineColumns().selfCheck.specs(); }

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
    refuseUnpaired(structureKind, strategy);
    if (strategy.refusal)
        if (const std::string why = strategy.refusal(vk.info()); !why.empty()) throw Error(why);
    const PinholeCamera camera = prepareSceneAndRays(*p, plan, strategy, caches, row);
    buildStructure(*p, structureKind, p->scene->traced);
    makeWorkload(*p, rayKind, camera, row);
    runMethod(*p, strategy, row);
    // Time: the kernel, uninstrumented, and Embree on the same rays, in rounds.
    EmbreeReference& embree = embreeFor(run, *p->scene, caches, row);
    timeBuilds(*p, structureKind, embree, caches, row);
    KernelTimer& kernel = *p->method.timer;
    p->rounds = std::make_unique<Rounds>(timedMethods(kernel, embree, p->workload.batch, p->path ? &*p->path : nullptr,
                                                     p->embreeHits, p->scratch, p->embreeRays),
                                         [&kernel] { return kernel.timeHostLoops(); }, roundsOptions(run), caches.started);
    return p;
}

void finishRun(RunInProgress& p, const FolderIdentity& folder, Caches& caches, Row& row, std::vector<TimingSample>& samples) {
    const RunConfig& run = *p.run;
    VulkanContext& vk = *p.vk;
    const std::vector<gpu::Ray>& rays = p.workload.batch.rays;
    samples = p.rounds->result().samples;
    samples.insert(samples.end(), p.buildSamples.begin(), p.buildSamples.end());
    writeTimingResults(run, vk, strategyType(run.getString("strategy.type")), p.path ? p.path->rays() : rays.size(),
                       p.rounds->result(), p.started, row);
    put(row, pipelineColumns().embreeRays, p.embreeRays);
    checkTimedRecords(p.method, p.shadingMismatch, rays.size());
    const RunImage imageOf{p};
    const HitImage image = imageOf(p.method.hits, p.scene->traced);
    judgeAgainstExact(p, imageOf, image, caches, row);
    writeAgreement(p, row);
    writeRunFiles(run, folder, image, row);
    if (vk.validationMessages().size() != p.messagesBefore)
        throw Error("the Vulkan validation layer reported: " + vk.validationMessages()[p.messagesBefore]);
    // The row is complete; a kernel that disagrees with its CPU reference fails it all the same.
    const std::string failure = instrumentedRunFailure(p.method, p.shadingMismatch, rays.size());
    if (!failure.empty()) throw Error(failure);
}

void executeRun(const ExperimentPlan& plan, const RunConfig& run, const FolderIdentity& folder, Caches& caches, Row& row,
                std::vector<TimingSample>& samples) {
    const std::unique_ptr<RunInProgress> p = prepareRun(plan, run, caches, row);
    while (!p->rounds->done()) p->rounds->runRound();
    finishRun(*p, folder, caches, row, samples);
}

std::string failureReason(const std::exception& e) {
    if (dynamic_cast<const std::bad_alloc*>(&e))
        return std::string("out of host memory (") + e.what() +
               "): the run needs more than the machine, or the process's address-space limit (ulimit -v), allows";
    return e.what();
}

}  // namespace rtbench
