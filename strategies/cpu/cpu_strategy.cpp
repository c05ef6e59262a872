#include "cpu_strategy.h"

#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <thread>

#include "schema/warnings.h"

#include "schema/column.h"

namespace rtbench {

namespace {

// Threads of the run: strategy.threads, or every hardware thread for 0; at most what TBB will
// run at once (its global limit: the hardware threads unless a global_control lowers it).
int hostThreads(const RunConfig& config, Row& row) {
    const std::int64_t asked = config.getInt("strategy.threads");
    const int wanted = asked > 0 ? int(asked) : int(std::max(1u, std::thread::hardware_concurrency()));
    const int limit = int(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
    if (wanted <= limit) return wanted;
    addWarning(row, "strategy.threads " + std::to_string(asked) + ": TBB runs at most " + std::to_string(limit) +
                        " threads here, so " + std::to_string(limit) + " traced the rays");
    return limit;
}

// The rays through the structure's traversal on `threads` TBB threads.
std::vector<gpu::HitRecord> traceOnHost(const Structure& structure, const std::vector<gpu::Ray>& rays,
                                        std::uint32_t query, tbb::task_arena& arena) {
    std::vector<gpu::HitRecord> hits;
    arena.execute([&] { hits = structure.trace(rays, query); });
    return hits;
}

// Times the trace again, a repetition at a time, with the host's clock. The structure is the
// runner's, kept until the run is finished.
class HostTimer : public KernelTimer {
public:
    HostTimer(const Structure& structure, std::vector<gpu::Ray> rays, std::uint32_t query, int threads,
              std::vector<gpu::HitRecord> counted)
        : structure_(structure), rays_(std::move(rays)), query_(query), arena_(threads), counted_(std::move(counted)) {}
    TimedBatch time(int warmups, int repetitions) override {
        std::vector<double> ms;
        for (int i = 0; i < warmups + repetitions; ++i) {
            const auto start = std::chrono::steady_clock::now();
            last_ = traceOnHost(structure_, rays_, query_, arena_);
            ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
        }
        return splitWarmups(ms, warmups);
    }
    void checkHits() override { expectSameHits(last_, counted_, "the CPU traversal"); }

private:
    const Structure& structure_;
    std::vector<gpu::Ray> rays_;
    std::uint32_t query_;
    tbb::task_arena arena_;
    std::vector<gpu::HitRecord> counted_, last_;
};

// The threads that traced (results schema 16): what ran, not what was asked.
const Column<int>& hostThreadsColumn() {
    static const Column<int> column({"host_threads", ColumnKind::Context, "threads",
                                     "cpu: the threads that traced the rays (strategy.threads, 0 made every hardware thread)", 0.0,
                                     false, {}, 16});
    return column;
}

StrategyRun runOnHost(VulkanContext&, const Structure& structure, const RayBatch& batch, const RunConfig& config,
                      const TimingOptions& timing, Row& row) {
    const int threads = hostThreads(config, row);
    put(row, hostThreadsColumn(), threads);
    tbb::task_arena arena(threads);
    StrategyRun run;
    run.hits = traceOnHost(structure, batch.rays, batch.query, arena);
    // Its own records are the CPU reference's: comparing them with it would check nothing.
    run.metrics = branchingMetrics(run.hits, 0, 0, structure.costs());
    run.metrics.laneUtilisation = -1.0;  // no subgroups
    run.metrics.simdEfficiency = run.metrics.purcellSimdEfficiency;
    run.cpuCompared = false;
    run.countsCompared = false;
    run.timer = std::make_unique<HostTimer>(structure, batch.rays, batch.query, threads, run.hits);
    if (timing.warmups + timing.repetitions > 0) {
        run.timer->time(timing.warmups, timing.repetitions);
        run.timer->checkHits();
    }
    return run;
}

}  // namespace

const StrategyType& cpuStrategyType() {
    static const StrategyType type = [] {
        StrategyType t;
        t.name = "cpu";
        t.help = "the structure's own traversal (its kernels' source compiled as C++, the CPU reference) on the host's "
                 "threads, timed on the host: the GPU against a CPU running the same algorithm (Christen 2005 §6.2.3); "
                 "kernel_* columns hold its wall time";
        t.keys = {{"strategy.threads", ValueType::Int, "cpu: TBB threads tracing the rays (0: every hardware thread)",
                   std::int64_t(0), false, 0, 4096}};
        t.keys.back().since = 16;
        t.columns = {hostThreadsColumn().spec()};
        t.trace = runOnHost;
        return t;
    }();
    return type;
}

}  // namespace rtbench
