// The sweep: for each run of the plan, its stages in order, each passing typed values to the next:
// the inputs (harness/run_inputs.h: device, scene, camera, Embree, exact reference, cached across
// the sweep) -> the ray batch (workloads/: the ray type) -> the method (methods/: the structure and
// the strategy, and their CPU model) -> the timing rounds (harness/timing_rounds.h) -> the
// measurements into the row (harness/run_metrics.h) -> the writers (runs.csv, samples.csv,
// context.json, images). Resumption, the failure policy (a failed run is a row with its reason)
// and the summary live here; `rtbench merge` in harness/shard_merge.cpp.
#include "runner.h"

#include <tbb/parallel_for.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <fstream>
#include <sstream>
#include <thread>

#include "columns.h"
#include "device/gpu_buffers.h"
#include "device/vulkan_context.h"
#include "embree_reference.h"
#include "exact_reference.h"
#include "images.h"
#include "interrupt_note.h"
#include "methods/registry.h"
#include "methods/tile_order.h"
#include "methods/triangle_store.h"
#include "noise_guard.h"
#include "path_check.h"
#include "plan_view.h"
#include "run_inputs.h"
#include "run_metrics.h"
#include "run_verdict.h"
#include "samples_check.h"
#include "statistics.h"
#include "timing_rounds.h"
#include "output_folder.h"
#include "scene/camera.h"
#include "core/error.h"
#include "scene/scene_description.h"
#include "version.h"
#include "workloads/registry.h"
#include "plan/warnings.h"

namespace rtbench {
namespace fs = std::filesystem;

namespace {

// The methods a run's rounds time: the kernel (its KernelTimer) and Embree rtcIntersect1 and
// rtcIntersect16 (any hit: rtcOccluded1 and 16) on the same rays (every generation of the path, for
// a strategy that traces it whole); the single rays' hits of the batch go to `embreeHits`, the
// rays each repetition traced to `embreeRays`.
std::vector<TimedMethod> timedMethods(KernelTimer& kernel, EmbreeReference& embree, const RayBatch& batch,
                                      std::vector<gpu::HitRecord>& embreeHits, std::vector<gpu::HitRecord>& scratch,
                                      std::uint64_t& embreeRays) {
    std::vector<TimedMethod> methods;
    methods.push_back({"kernel", [&kernel](int warmups, int repetitions) { return kernel.time(warmups, repetitions); }});
    for (EmbreeMode mode : {EmbreeMode::Intersect1, EmbreeMode::Intersect16})
        methods.push_back({mode == EmbreeMode::Intersect1 ? "embree1" : "embree16",
                           [&embree, &batch, &embreeHits, &scratch, &embreeRays, mode](int warmups, int repetitions) {
                               // What the kernel traced: the batch, or (RayBatch::path) every generation of its path,
                               // those before the batch as closest-hit queries.
                               auto trace = [&](std::vector<gpu::HitRecord>& hits) {
                                   double ms = 0.0;
                                   embreeRays = batch.rays.size();
                                   if (batch.path)
                                       for (std::size_t g = 0; g + 1 < batch.path->generations.size(); ++g) {
                                           ms += embree.trace(*batch.path->generations[g].rays, mode, scratch, gpu::kQueryClosest);
                                           embreeRays += batch.path->generations[g].rays->size();
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
    RayBatch tiled;  // camera.tile: the batch in tile order, as the method traced it
    StrategyRun method;
    std::vector<gpu::HitRecord> embreeHits, scratch;  // written by the Embree batches
    std::uint64_t embreeRays = 0;                     // the rays each of them traced
    std::unique_ptr<Rounds> rounds;
};

// A record naming a triangle the scene lacks (a kernel gone wrong) is no hit to judge, shade or
// shoot rays from: the run fails here, before anything reads the scene at that index.
void refuseForeignTriangles(const std::vector<gpu::HitRecord>& hits, std::size_t triangles) {
    for (std::size_t i = 0; i < hits.size(); ++i)
        if (hits[i].primitive != gpu::kNoHit && hits[i].primitive >= triangles)
            throw Error("the kernel's record of ray " + std::to_string(i) + " names triangle " +
                        std::to_string(hits[i].primitive) + ", but the scene has " + std::to_string(triangles));
}

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
    refuseUnpaired(structureKind, strategy);
    if (strategy.refusal)
        if (const std::string why = strategy.refusal(vk.info()); !why.empty()) throw Error(why);

    // Scene and rays. Refuse before allocating: the per-ray buffers on the device, together (a
    // binding holds one batch: the strategies trace a longer stream in batches, and check the
    // batches' structure copies and the largest traversal state again), and the per-ray host data.
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
    const std::uint64_t streamRays = std::uint64_t(p->width) * p->height;
    std::vector<BufferSize> perRay = rayBufferSizes(streamRays);
    if (strategy.ownBytesPerRay)
        perRay.push_back({strategy.name + "'s own per-ray buffers", streamRays * strategy.ownBytesPerRay});
    refuseOversizedTotal(vk.info(), perRay);
    refuseOversizedRayStream(std::uint64_t(p->width) * p->height);
    p->cameraRays = generatePrimaryRays(camera, p->width, p->height);
    validateRays(p->cameraRays);

    // Structure: built for the camera rays (brute force refuses by their count, auto chooses by
    // its prediction for them).
    p->structure = structureKind.build(mesh, p->cameraRays, run, vk.info());
    Structure& structure = *p->structure;
    structure.setArithmetic({run.getString("intersection.test") == "watertight" ? gpu::kTriangleTestWatertight
                                                                                : gpu::kTriangleTestMollerTrumbore,
                             run.getString("intersection.division") == "integer" ? gpu::kDivisionInteger
                                                                                 : gpu::kDivisionDouble});
    structure.buildOnDevice(vk);

    // Workload: the batch of rays the run measures (rays.type), from the camera rays and, after
    // the first hit, from the structure's hits of them.
    const WorkloadInputs inputs{run, mesh, p->cameraRays, structure, camera.up,
                                [&run](glm::vec3 point) { return sceneTransform(run, point); }};
    p->workload = rayKind.make(inputs, row);
    if (const std::string query = run.getString("rays.query"); query != "own")
        p->workload.batch.query = query == "any" ? gpu::kQueryAny : gpu::kQueryClosest;
    if (strategy.tracesPath)  // the whole path on the device: the generations before the batch and the passes
        p->workload.batch.path = std::make_shared<const BatchPath>(batchPath(p->workload, p->cameraRays, mesh));
    const RayBatch& batch = p->workload.batch;
    const std::vector<gpu::Ray>& rays = batch.rays;
    validateRays(rays);
    p->shadingMismatch = checkShadingOnDevice(vk, unsigned(run.getInt("strategy.workgroup_size")), mesh, p->cameraRays,
                                              p->workload, row);
    row["rays"] = std::to_string(rays.size());
    row["query"] = queryName(batch.query);
    structure.writeColumns(row);
    row["structure_bytes"] = std::to_string(structure.memoryBytes);
    row["structure_bytes_per_triangle"] = formatNumber(double(structure.memoryBytes) / double(std::max<std::size_t>(mesh.triangles.size(), 1)));
    row["structure_build_ms"] = formatNumber(structure.buildMs, 4);
    const double predicted = structure.predictedWork(rays);
    row["predicted_work_per_ray"] = predicted < 0 ? "" : formatNumber(predicted / double(rays.size()));

    // Method: the strategy runs the structure's kernels once, instrumented, and checks them
    // against its CPU reference.
    TimingOptions timing;
    timing.workgroupSize = unsigned(run.getInt("strategy.workgroup_size"));
    timing.warmups = timing.repetitions = 0;  // timed in rounds with Embree
    // camera.tile (Purcell §5.3): the method traces the rays tile by tile; its records come back
    // in the batch's order. Embree traces them row by row.
    const unsigned tile = run.has("camera.tile") ? unsigned(run.getInt("camera.tile")) : 0u;  // camera rays only
    if (tile && strategy.tracesPath)
        throw Error("camera.tile: strategy.type = " + strategy.name + " traces the camera rays in the order they are made");
    const std::vector<std::uint32_t> order = tileOrder(p->width, p->height, tile);
    if (!order.empty()) p->tiled = inTileOrder(batch, order);
    p->method = strategy.run(vk, structure, order.empty() ? batch : p->tiled, run, timing, row);
    if (!order.empty()) p->method.hits = inBatchOrder(p->method.hits, order);
    row["cpu_reference_mismatches"] = p->method.cpuCompared ? std::to_string(p->method.cpuMismatches) : "";
    refuseForeignTriangles(p->method.hits, mesh.triangles.size());
    row["cpu_counts_match"] = !p->method.countsCompared ? "" : p->method.countsMismatch.empty() ? "1" : "0";
    writeArchitectureColumns(p->method.metrics, structure, rays.size(), row);

    // Time: the kernel, uninstrumented, and Embree on the same rays, in rounds.
    EmbreeReference& embree = embreeFor(run, scene, caches, row);
    KernelTimer& kernel = *p->method.timer;
    p->rounds = std::make_unique<Rounds>(timedMethods(kernel, embree, batch, p->embreeHits, p->scratch, p->embreeRays),
                                         [&kernel] { return kernel.timeHostLoops(); }, roundsOptions(run), caches.started);
    return p;
}

void finishRun(RunInProgress& p, const FolderIdentity& folder, Caches& caches, Row& row, std::vector<TimingSample>& samples) {
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
    writeTimingResults(run, vk, workload.batch.path ? workload.batch.path->rays() : rays.size(), p.rounds->result(), p.started, row);
    row["embree_rays"] = std::to_string(p.embreeRays);
    checkTimedRecords(method, p.shadingMismatch, rays.size());

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
        row["exact_parent_wrong"] = std::to_string(pathsLeavingWrongHits(exactReferenceFor(run, scene.full, caches), p.cameraRays,
                                                                         workload, exact.rays, scene.sameTriangles));

    // Metrics: agreement with Embree.
    const Agreement a = compareHits(method.hits, embreeHits, query);
    row["hits"] = std::to_string(method.metrics.work.hits);
    row["hit_miss_agreement"] = formatNumber(a.hitMissAgreement, 8);
    row["hit_miss_mismatches"] = std::to_string(a.hitMissMismatches);
    if (a.primitivesCompared) {
        row["same_primitive_agreement"] = formatNumber(a.samePrimitiveAgreement, 8);
        row["rel_distance_error_mean"] = formatNumber(a.relDistanceErrorMean, 4);
        row["rel_distance_error_max"] = formatNumber(a.relDistanceErrorMax, 4);
        row["primitive_mismatches"] = std::to_string(a.primitiveMismatches);
    }

    // Writers: images, or the per-ray records to make them later.
    folder.check();  // still the folder the sweep opened
    const std::string prefix = (fs::path(folder.path()) / ("run-" + row["run"])).string();
    const bool wantImages = run.getBool("output.images");
    if (run.getBool("output.hit_records") || (wantImages && !imagesSupported())) writeHitRecords(prefix + ".hits", image, row["run"], row["config_hash"]);
    if (wantImages && imagesSupported()) writeImages(prefix, image, run.getBool("output.exr"));
    if (wantImages && !imagesSupported() && run.getBool("output.exr"))
        addWarning(row, "output.exr: built without OpenImageIO, no EXR written (rtbench images makes PNGs only)");

    if (vk.validationMessages().size() != p.messagesBefore)
        throw Error("the Vulkan validation layer reported: " + vk.validationMessages()[p.messagesBefore]);
    // The row is complete; a kernel that disagrees with its CPU reference fails it all the same.
    const std::string failure = instrumentedRunFailure(method, p.shadingMismatch, rays.size());
    if (!failure.empty()) throw Error(failure);
}

// One run, whole: prepared, timed round after round, finished.
void executeRun(const ExperimentPlan& plan, const RunConfig& run, const FolderIdentity& folder, Caches& caches, Row& row,
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
    if (!plan.settings.empty()) j["settings"] = plan.settings;  // the command line's --set, applied over config_text
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
                                {"subgroup_size", d.subgroupSize}, {"lock_step_subgroups", d.lockStepSubgroups},
                                {"max_storage_buffer_range", d.maxStorageBufferRange},
                                {"timestamp_period_ns", d.timestampPeriodNs}, {"ray_query", d.rayQuery}});
    }
    j["plan"] = Json::array();
    for (const RunConfig& run : plan.runs)
        j["plan"].push_back({{"run", runNumber(run)}, {"config_hash", run.hash()}, {"label", run.label()}});
    return j;
}

// A failed run's error: what the exception says, and for an allocation that failed, what ran out.
std::string failureReason(const std::exception& e) {
    if (dynamic_cast<const std::bad_alloc*>(&e))
        return std::string("out of host memory (") + e.what() +
               "): the run needs more than the machine, or the process's address-space limit (ulimit -v), allows";
    return e.what();
}

// A run's identity beyond its parameters (config_hash): the commit of the binary, the device it
// ran on and the contents of the files its scene was made from. A row of an earlier invocation
// stands for a run of this plan only when all of them are equal.
std::string identity(const Row& row) {
    std::string key;
    for (const char* column : {"run", "config_hash", "git_commit", "device", "driver", "cpu", "inputs_hash"})
        key += (key.empty() ? "" : "|") + cellText(row, column);
    return key;
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

// "file:line" of the first line of the config text that gives `value` as a quoted string, else
// the file alone (a value from --set, or written another way).
std::string whereInConfig(const ExperimentPlan& plan, const std::string& value) {
    std::istringstream lines(plan.configText);
    std::string line;
    for (int n = 1; std::getline(lines, line); ++n)
        if (line.find("\"" + value + "\"") != std::string::npos || line.find("'" + value + "'") != std::string::npos)
            return plan.configPath + ":" + std::to_string(n);
    return plan.configPath;
}

// Every scene.source the runs name exists (scene/scene_description.h checkSceneSource);
// else an error naming the config's line, the key, the source and its runs.
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
            throw Error(whereInConfig(plan, source) + ": key 'scene.source' = \"" + source + "\" (run " + which + "): " + e.what() +
                        "; nothing was run");
        }
    }
}

// samples.csv rows of one run as the timing samples they were (an interrupted sweep's rounds).
std::vector<TimingSample> timingSamples(const std::vector<Row>& rows) {
    std::vector<TimingSample> samples;
    for (const Row& r : rows)
        samples.push_back({r.at("method"), std::stoi(r.at("round")), std::stoi(r.at("repetition")), cellNumber(r.at("ms")),
                           cellNumber(r.at("t_s"))});
    std::stable_sort(samples.begin(), samples.end(), [](const TimingSample& a, const TimingSample& b) { return a.round < b.round; });
    return samples;
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

std::string consoleNumber(const std::string& cell) {
    char* end = nullptr;
    const double value = std::strtod(cell.c_str(), &end);
    if (cell.empty() || *end != '\0' || !std::isfinite(value)) return cell;
    char text[32];
    std::snprintf(text, sizeof text, std::fabs(value) >= 100.0 ? "%.0f" : "%.3g", value);
    return text;
}

std::string summaryTable(const std::vector<Row>& rows) {
    // Speed (with the ratio's 95% interval) and the exact accuracy; the swept parameters last, whole.
    std::ostringstream out;
    auto get = [](const Row& r, const char* key) {
        auto it = r.find(key);
        return it == r.end() || it->second.empty() ? std::string("-") : it->second;
    };
    auto number = [&](const Row& r, const char* key) { return consoleNumber(get(r, key)); };
    out << std::left << std::setw(5) << "run" << std::right << std::setw(13) << "kernel Mr/s" << std::setw(14)
        << "Embree1 Mr/s" << std::setw(10) << "ratio" << std::setw(22) << "ratio 95% interval" << std::setw(12)
        << "wrong ppm" << std::setw(9) << "status" << "  " << std::left << "parameters (wrong ppm: against the exact reference)\n";
    for (const Row& r : rows) {
        const std::string interval = get(r, "speed_ratio_ci_low") == "-" ? "-"
                                     : "[" + number(r, "speed_ratio_ci_low") + ", " + number(r, "speed_ratio_ci_high") + "]";
        out << std::left << std::setw(5) << get(r, "run") << std::right << std::setw(13) << number(r, "kernel_mrays_s")
            << std::setw(14) << number(r, "embree1_mrays_s") << std::setw(10) << number(r, "speed_ratio_vs_embree1") << std::setw(22)
            << interval << std::setw(12) << number(r, "exact_wrong_ppm") << std::setw(9) << get(r, "status") << "  " << std::left
            << get(r, "label") << (get(r, "timing_warning") == "-" ? "" : " [timing_warning]")
            << (get(r, "warnings") == "-" ? "" : " [warning]") << "\n";
    }
    for (const Row& r : rows)
        if (get(r, "status") == "failed") out << "run " << get(r, "run") << " failed: " << get(r, "error") << "\n";
    return out.str();
}

namespace {
// Rows of two lists by run number (this invocation's and those --filter carried over).
std::vector<Row> inRunOrder(std::vector<Row> rows, const std::vector<Row>& more) {
    rows.insert(rows.end(), more.begin(), more.end());
    std::stable_sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) { return a.at("run") < b.at("run"); });
    return rows;
}

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
    std::set<const RunConfig*> selected;  // --filter's
    for (const RunConfig* run : filterRuns(plan, options.filters)) selected.insert(run);
    std::vector<const RunConfig*> mine;
    for (const RunConfig& run : plan.runs)
        if (run.index % options.shardCount == options.shardIndex &&
            (options.onlyRuns.empty() || options.onlyRuns.count(runNumber(run))) && selected.count(&run))
            mine.push_back(&run);
    if (mine.empty() && !options.filters.empty())
        throw Error(plan.configPath + ": no run matches --filter (rtbench plan --filter shows what each selects)");
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
    const FolderIdentity folder(result.folder);  // checked again before every write below
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
    std::set<const Row*> samplesNotItsOwn;         // earlier ok rows whose samples are missing or another's
    const auto earlierByRun = samplesByRun(earlierSamples);
    for (std::size_t k = 0; k < mine.size(); ++k) {
        const RunConfig& run = *mine[k];
        const VulkanContext& vk = deviceFor(run, caches);
        Row& row = rows[k] = identityRow(run, gitCommit(), vk.info().name, vk.info().driver, cpuModel());
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
        if (!samplesProblem(*previous->second, earlierByRun).empty()) {  // a row is kept with its evidence only
            samplesNotItsOwn.insert(previous->second);
            continue;
        }
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
    // --filter: the earlier rows of the plan's runs it leaves out stand as they are (not re-run,
    // not set aside), with their samples.
    std::vector<Row> carried;
    if (!options.filters.empty())
        for (const Row& row : earlierRows)
            if (planned.count(row.at("run") + "|" + row.at("config_hash")) && !planRow.count(row.at("run"))) {
                carried.push_back(row);
                keptEarlier.insert(&row);
            }
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
                                 : samplesNotItsOwn.count(&row)                                ? "samples missing or not its own"
                                                                                               : "other input files";
            ++why[reason];
        }
    // The samples of kept rows stand with them; the rest (superseded rows', and those of a run
    // interrupted before its row was written) are set aside.
    std::set<std::string> keptRuns;
    for (const Row* row : keptEarlier) keptRuns.insert(row->at("run") + "|" + row->at("config_hash"));
    // An interleaved sweep appends each round's samples as it goes: the rounds a killed invocation
    // finished of a run with no row stand, and its timing goes on from them.
    std::set<std::string> rowRuns, toRun;
    for (const Row& row : earlierRows) rowRuns.insert(row.at("run") + "|" + row.at("config_hash"));
    const bool interleaved = first.getString("experiment.order") == "interleaved";
    for (std::size_t k = 0; k < mine.size(); ++k)
        if (!kept[k] && interleaved && !options.force) toRun.insert(rows[k].at("run") + "|" + rows[k].at("config_hash"));
    std::vector<Row> keptSamples, supersededSamples;
    std::map<std::string, std::vector<Row>> resumedSamples;  // "run|config_hash" -> its finished rounds
    for (Row& sample : earlierSamples) {
        const std::string key = sample.at("run") + "|" + sample.at("config_hash");
        if (keptRuns.count(key)) keptSamples.push_back(std::move(sample));
        else if (toRun.count(key) && !rowRuns.count(key)) resumedSamples[key].push_back(std::move(sample));
        else supersededSamples.push_back(std::move(sample));
    }
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
        writeCsv(csvPath, columns, inRunOrder(keptRows, carried));
        for (const auto& [key, samples] : resumedSamples) keptSamples.insert(keptSamples.end(), samples.begin(), samples.end());
        writeCsv(samplesPath, sampleColumns(), keptSamples);  // the kept runs' samples first, then resumed rounds
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
    int rowsWritten = int(std::count(kept.begin(), kept.end(), true));
    if (!options.commandLine.empty())  // a sweep the user started (not check's re-run into a folder of its own)
        setInterruptNote(interruptNote(rowsWritten, int(mine.size()), csvPath, options.commandLine));
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
                std::cout << " " << consoleNumber(row["kernel_mrays_s"]) << " Mrays/s (Embree " << consoleNumber(row["embree1_mrays_s"])
                          << "), hit/miss agreement " << row["hit_miss_agreement"] << ", " << consoleNumber(row["wall_s"]) << " s\n";
            else
                std::cout << " FAILED: " << row["error"] << "\n";
        }
        result.warned += !row["warnings"].empty() || !row["timing_warning"].empty();
        if (!row["warnings"].empty() && !options.quiet)
            std::cerr << "[rtbench] run " << row["run"] << " warning: " << row["warnings"] << "\n";
        if (!row["timing_warning"].empty() && !options.quiet)
            std::cerr << "[rtbench] run " << row["run"] << " timing warning: " << row["timing_warning"]
                      << " (not a timing of record)\n";
        folder.check();  // the folder opened, not one put in its place since
        appendCsvRows(samplesPath, sampleColumns(), sampleRows(row, samples));
        appendCsvRow(csvPath, columns, row);  // an interrupt loses nothing done
        ++rowsWritten;
        if (!options.commandLine.empty())
            setInterruptNote(interruptNote(rowsWritten, int(mine.size()), csvPath, options.commandLine));
    };
    // Progress: runs done, elapsed, and an estimate for the rest from the runs executed so far.
    // The time left: an earlier row's wall_s for each run still to run that has one (a --force
    // re-run, another commit), the mean of the runs run so far for the others; unknown before any.
    std::vector<double> tookBefore(mine.size(), -1.0);  // each run's earlier wall_s, -1 where none
    {
        const std::map<std::string, double> earlierWall = earlierWallSeconds(earlierRows);
        for (std::size_t k = 0; k < mine.size(); ++k) {
            const auto it = earlierWall.find(rows[k].at("run") + "|" + rows[k].at("config_hash"));
            if (it != earlierWall.end()) tookBefore[k] = it->second;
        }
    }
    auto secondsLeft = [&](std::size_t from) {
        double known = 0.0;
        std::size_t unknown = 0;
        for (std::size_t j = from; j < mine.size(); ++j) {
            if (kept[j]) continue;
            if (tookBefore[j] >= 0.0) known += tookBefore[j];
            else ++unknown;
        }
        if (unknown == 0) return known;
        return executed > 0 ? known + executedSeconds / executed * double(unknown) : -1.0;
    };
    auto progress = [&](const char* what, std::size_t k) {
        if (options.quiet) return;
        std::cout << "[" << what << " " << k + 1 << "/" << mine.size() << ", " << std::fixed << std::setprecision(0)
                  << since(experimentStart) << " s";
        const double left = std::string(what) == "run" ? secondsLeft(k) : -1.0;
        if (left >= 0.0) std::cout << ", ~" << left << " s left";
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
                executeRun(plan, *mine[k], folder, caches, rows[k], samples);
            } catch (const std::exception& e) {
                error = failureReason(e);
            }
            record(k, error, since(start), samples);
        }
    } else {
        // Interleaved (experiment.order): every run is prepared (its instrumented run and checks),
        // then timed one round at a time across the sweep, round r of every run before round r + 1
        // of any, so runs compared in one table were timed under the same conditions; then each is
        // finished. Every prepared run keeps its device buffers until then.
        // Each round's samples are appended as it ends (`appended`: a run's samples in the file), so
        // a killed sweep resumes from the rounds it finished (resumedSamples).
        std::vector<std::unique_ptr<RunInProgress>> running(mine.size());
        std::vector<double> seconds(mine.size(), 0.0);
        std::vector<std::size_t> appended(mine.size(), 0);
        for (std::size_t k = 0; k < mine.size(); ++k) {
            if (kept[k]) continue;
            progress("prepare", k);
            const auto start = Clock::now();
            try {
                running[k] = prepareRun(plan, *mine[k], caches, rows[k]);
                const auto resumed = resumedSamples.find(rows[k].at("run") + "|" + rows[k].at("config_hash"));
                if (resumed != resumedSamples.end()) {
                    running[k]->rounds->resume(timingSamples(resumed->second));
                    appended[k] = resumed->second.size();
                    if (!options.quiet) std::cout << " prepared; " << running[k]->rounds->result().rounds << " round(s) kept from the interrupted sweep\n";
                } else if (!options.quiet) {
                    std::cout << " prepared\n";
                }
            } catch (const std::exception& e) {
                record(k, failureReason(e), since(start), {});
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
                    const std::vector<TimingSample>& taken = running[k]->rounds->result().samples;
                    folder.check();
                    appendCsvRows(samplesPath, sampleColumns(),
                                  sampleRows(rows[k], std::vector<TimingSample>(taken.begin() + appended[k], taken.end())));
                    appended[k] = taken.size();
                } catch (const std::exception& e) {
                    running[k].reset();  // its buffers go now
                    if (!options.quiet) std::cout << "[round " << round + 1 << "] " << mine[k]->label() << ":";
                    record(k, failureReason(e), seconds[k] + since(start), {});
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
                finishRun(*running[k], folder, caches, rows[k], samples);
            } catch (const std::exception& e) {
                error = failureReason(e);
            }
            running[k].reset();
            // Its rounds' samples are in the file already: the row and any samples after them.
            record(k, error, seconds[k] + since(start),
                   std::vector<TimingSample>(samples.begin() + std::min(appended[k], samples.size()), samples.end()));
        }
    }
    result.rows = rows;
    const std::vector<Row> written = inRunOrder(rows, carried);
    folder.check();
    writeCsv(csvPath, columns, written);  // in plan order
    // Complete when every planned run of this file has its row (--filter may leave some without).
    const std::size_t plannedHere = std::size_t(std::count_if(plan.runs.begin(), plan.runs.end(), [&](const RunConfig& run) {
        return run.index % options.shardCount == options.shardIndex;
    }));
    const bool complete = options.filters.empty() || written.size() == plannedHere;
    writeJson(contextPath, contextJson(plan, options, caches, started, complete));
    if (!options.commandLine.empty()) setInterruptNote("");
    return result;
}

Row identityRow(const RunConfig& run, const std::string& commit, const std::string& device, const std::string& driver,
                const std::string& cpu) {
    Row row;
    for (const auto& [key, value] : run.values)
        for (const auto& [column, cell] : keyCells(keySpec(key), value)) row[column] = cell;
    row["run"] = runNumber(run);
    row["label"] = run.label();
    row["sweep"] = run.sweep;
    row["config_hash"] = run.hash();
    row["git_commit"] = commit;
    row["device"] = device;
    row["driver"] = driver;
    row["cpu"] = cpu;
    return row;
}

}  // namespace rtbench
