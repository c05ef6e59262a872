// One run as a pipeline of stages, each passing typed values to the next: scene -> rays ->
// structure -> method (the strategy on the device, checked against the structure's CPU reference)
// -> timing in rounds with Embree on the same rays -> references (the exact first hits of a sample)
// -> verdict -> the row and the run's files. prepareRun does all up to the timing, Rounds::runRound
// the timing a round at a time (harness/sweep.h interleaves them), finishRun the rest.
#pragma once
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "harness/config.h"
#include "harness/noise_guard.h"
#include "harness/output_folder.h"
#include "harness/run_inputs.h"
#include "harness/timing_rounds.h"
#include "strategies/strategy.h"
#include "structures/structure.h"
#include "rays/workload.h"
#include "scene/camera.h"

namespace rtbench {

// A run from its scene to its timing: what its rounds and the rest of it need. It holds the
// run's device buffers (the strategy's timer) until the run is finished.
struct RunInProgress {
    const RunConfig* run = nullptr;
    VulkanContext* vk = nullptr;
    std::size_t messagesBefore = 0;
    CpuTimes started;  // the noise guard's window: from here to the end of the timing
    std::optional<RunScene> scene;
    unsigned width = 0, height = 0;
    std::shared_ptr<const CameraFrame> cameraFrame;  // what the camera rays are made of
    std::vector<gpu::Ray> cameraRays;
    Workload workload;  // the batch the run measures
    // A strategy that traces the whole path: the generations that end in the batch and the passes
    // between (pointing into `workload` and `cameraRays`); none for a batch strategy.
    std::optional<BatchPath> path;
    std::string shadingMismatch;  // how the device's shading passes differ from the CPU's ("" if not)
    std::unique_ptr<Structure> structure;
    RayBatch tiled;  // camera.tile: the batch in tile order, as the method traced it
    StrategyRun method;
    std::vector<gpu::HitRecord> embreeHits, scratch;  // written by the Embree batches
    std::uint64_t embreeRays = 0;                     // the rays each of them traced
    std::unique_ptr<Rounds> rounds;
    std::vector<TimingSample> buildSamples;  // experiment.build_rounds
};

// The columns the stages write: the batch (rays, query), the camera and the structure, and the
// agreement with Embree on the same rays, each in its place among runs.csv's (harness/columns.cpp).
const std::vector<ColumnSpec>& batchColumns();
const std::vector<ColumnSpec>& cameraAndStructureColumns();
const std::vector<ColumnSpec>& agreementColumns();
// The exact reference's sample (exact_rays, _ties, _ms, _parent_wrong), embree_rays, and the
// self-checks against the CPU reference (cpu_reference_mismatches, cpu_counts_match).
const std::vector<ColumnSpec>& exactSampleColumns();
const ColumnSpec& embreeRaysColumn();
const std::vector<ColumnSpec>& selfCheckColumns();

// Everything up to the timing: the row gets every value known before it. Throws on a run that
// cannot be run (its reason goes into the row as a failed run's error).
std::unique_ptr<RunInProgress> prepareRun(const ExperimentPlan& plan, const RunConfig& run, Caches& caches, Row& row);

// After the timing: the timing columns, the references, the agreement with Embree, the images;
// `samples` gets the run's timing samples. A self-check that fails throws after the row is complete.
void finishRun(RunInProgress& p, const FolderIdentity& folder, Caches& caches, Row& row, std::vector<TimingSample>& samples);

// One run, whole: prepared, timed round after round, finished.
void executeRun(const ExperimentPlan& plan, const RunConfig& run, const FolderIdentity& folder, Caches& caches, Row& row,
                std::vector<TimingSample>& samples);

// A failed run's error: what the exception says, and for an allocation that failed, what ran out.
std::string failureReason(const std::exception& e);

}  // namespace rtbench
