// Which pass the multipass ray caster runs next (Purcell et al. 2002 §3.2; Christen 2005 §5.6):
// decided on the host from the number of rays in each active state after the last pass (the
// occlusion query of the theses), shared by the GPU strategy and the CPU simulator.
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace rtbench {

enum class PassKind { Setup = 0, Traverse = 1, Intersect = 2, Write = 3 };
constexpr int kPassKinds = 4;
const char* passKindName(PassKind kind);

struct MultipassOptions {
    unsigned traverseStepsPerPass = 1;  // K: DDA steps per traverse pass (Purcell: 4)
    unsigned intersectionsPerPass = 1;  // M: triangle tests per intersect pass (Purcell: 2)
    bool suppressFinishedReads = false; // rays done mid-pass skip the unrolled rest's reads
    // "oracle": intersect when waiting / active >= oracleThreshold, else traverse (0: as soon as
    // any ray waits; 0.2: Purcell's choice). "naive": traverse until no ray traverses, then
    // intersect until no ray waits, and again.
    std::string scheduling = "oracle";
    double oracleThreshold = 0.2;
    // What the waiting fraction is of: "active" (traversing + waiting rays; Purcell's "percentage of
    // rays requiring intersection vs. traversal") or "all" (the stream's rays, misses and finished
    // rays included: another reading of "20% of the rays").
    std::string oracleBasis = "active";
    std::uint64_t maxPasses = 0;  // 0: automatic cap from the structure (Structure::walkBounds)
    std::uint64_t batchRays = 0;  // rays per batch, each its own pass loop (0: what one binding holds)
    // strategy.control: false ("host"), the host's oracle reads the counts back after each pass and
    // every pass walks the whole stream through the stencil; true ("device"), the oracle runs on
    // the device and each pass serves a compacted list of its rays (multipass_oracle.comp).
    bool deviceControl = false;
    // strategy.list_partitions, with the control on the device: each ray list in this many
    // partitions (1..kMaxListPartitions), each with its own length; a pass's workgroups append to
    // them in equal runs (multipass_common.glsl mpPartition).
    unsigned listPartitions = 2;
};

// floor(threshold * 2^31), the oracle's threshold as the shared decision (multipass_oracle.glsl)
// applies it; throws outside [0, 1].
std::uint32_t oracleThresholdQ31(double threshold);

static_assert(int(PassKind::Setup) == 0 && int(PassKind::Traverse) == 1 && int(PassKind::Intersect) == 2 &&
              int(PassKind::Write) == 3, "PassKind is kernels/gpu_layout.h kPass*");

class PassScheduler {
public:
    // Throws when the options' oracle threshold is outside [0, 1]. `streamRays`: the rays of the
    // stream (its batch), the basis of the waiting fraction with oracle_basis = all.
    PassScheduler(const MultipassOptions& options, std::uint64_t streamRays)
        : thresholdQ31_(oracleThresholdQ31(options.oracleThreshold)), naive_(options.scheduling == "naive"),
          basisRays_(options.oracleBasis == "all" ? std::uint32_t(streamRays) : 0u) {}
    // The next pass after one that left `traversing` and `waiting` rays active; Write when none.
    PassKind next(std::uint64_t traversing, std::uint64_t waiting);

private:
    std::uint32_t thresholdQ31_;  // the oracle threshold as the shared decision applies it
    bool naive_;                  // Christen's naive schedule
    std::uint32_t basisRays_;     // the waiting fraction's basis: 0, the active rays; else the stream's
    PassKind naivePhase_ = PassKind::Traverse;
};

// What one pass reports about the rays it served (the kernels' atomics, the simulator's sums).
struct PassSums {
    std::uint64_t traversing = 0, waiting = 0;  // served rays in each active state after the pass
    std::uint64_t useful = 0;                   // rays served
    std::uint64_t stencilWrites = 0, structureReads = 0, triangleReads = 0;
    std::uint64_t stackEntries = 0;  // node-stack entries pushed or popped (BVH)
    PassSums& operator+=(const PassSums& o) {
        traversing += o.traversing, waiting += o.waiting, useful += o.useful;
        stencilWrites += o.stencilWrites, structureReads += o.structureReads, triangleReads += o.triangleReads;
        stackEntries += o.stackEntries;
        return *this;
    }
};

// Counts of one multipass run, the same whether the GPU or the simulator produced them.
struct MultipassCounts {
    std::array<std::uint64_t, kPassKinds> passes{};  // by PassKind
    std::uint64_t usefulTraverse = 0;   // rays served, summed over traverse passes
    std::uint64_t usefulIntersect = 0;  // rays served, summed over intersect passes
    std::uint64_t stencilWrites = 0;  // all passes
    std::uint64_t structureReads = 0;  // grid: cell offsets; BVH: nodes
    std::uint64_t triangleReads = 0;
    std::uint64_t stackEntries = 0;  // node-stack entries pushed or popped (BVH), all passes
    std::vector<PassKind> sequence;   // every pass in order (setup first, write last)
    // The ray slots the traverse and intersect passes walk: each such pass times the rays of its
    // stream (its batch's, when the stream runs in batches). Purcell's SIMD efficiency divides the
    // rays served by it; every slot reads its ray's stencil byte. With the control on the device a
    // pass is dispatched over its compacted list instead: its slots are the list's rays, each read.
    std::uint64_t streamSlots = 0;
    // The same over the whole stream (its batch's) whatever the control: Purcell's SIMD
    // efficiency's denominator, misses included (equal to streamSlots under the host's control).
    std::uint64_t wholeStreamSlots = 0;
    // Rays a pass (setup included) left active, summed: with the control on the device, the
    // entries appended to the ray lists.
    std::uint64_t listAppends = 0;

    std::uint64_t totalPasses() const { return passes[0] + passes[1] + passes[2] + passes[3]; }
    bool operator==(const MultipassCounts&) const = default;
    // The counts of a stream run in batches, one batch after another: passes and events add up,
    // the sequences follow each other.
    MultipassCounts& operator+=(const MultipassCounts& batch);
};

// The pass loop of both the GPU strategy and the simulator over a stream of `rays` rays: setup,
// then the scheduler's passes until no ray is active, then write. `pass` runs one pass. Throws
// rtbench::Error when `cap` passes have run and rays are still active.
// `afterPass`, when given, sees the rays active in each state after every pass but the write.
MultipassCounts runPassLoop(const MultipassOptions& options, std::uint64_t cap, std::uint64_t rays,
                            const std::function<PassSums(PassKind)>& pass,
                            const std::function<void(std::uint64_t traversing, std::uint64_t waiting)>& afterPass = {});

// A cap on passes: 4 x (ceil(Vmax / K) + ceil(Vmax * Lmax / M)) + 16, where Vmax bounds the
// cells (voxels, nodes) one ray visits and Lmax the triangles in one (at least 1): a heuristic
// bound (four times one ray's most passes), not a proof: every pass serves some ray, but rays out
// of step add passes. A run that reaches it fails naming the cap (strategy.max_passes raises it).
std::uint64_t multipassPassCap(std::uint64_t maxCellsPerRay, std::uint64_t maxTrianglesPerCell,
                               const MultipassOptions& options);

}  // namespace rtbench
