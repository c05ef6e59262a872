#include "cache_replay.h"

#include <variant>

#include "methods/cache/memory_trace.h"
#include "strategies/multipass/multipass_simulator.h"
#include "core/error.h"
#include "schema/column.h"

namespace rtbench {

namespace {

void placeStructure(MemoryTrace& trace, const Structure& structure) {
    for (const StructureBuffer& b : structure.buffers()) trace.place(b.data, b.bytes);
}

// The accounting's bytes of one data type.
std::uint64_t accountedBytes(const Bandwidth& b, MemoryKind kind) {
    switch (kind) {
        case MemoryKind::Stencil:
            return b.stencil;
        case MemoryKind::State:
            return b.state;
        case MemoryKind::Stack:
            return b.stack;
        case MemoryKind::Cells:
            return b.cells;
        case MemoryKind::TriangleList:
            return b.triangleList;
        case MemoryKind::Vertices:
            return b.vertices;
        case MemoryKind::Output:
            return b.output;
    }
    return 0;
}

constexpr MemoryKind kReadKinds[] = {MemoryKind::Stencil, MemoryKind::State,        MemoryKind::Stack,
                                     MemoryKind::Cells,   MemoryKind::TriangleList, MemoryKind::Vertices};

}  // namespace

CacheSimulator branchingCacheReplay(const Structure& structure, const std::vector<gpu::Ray>& rays, std::uint32_t query,
                                    const CacheConfig& config) {
    CacheSimulator cache(config);
    MemoryTrace trace(cache);
    placeStructure(trace, structure);
    std::vector<gpu::HitRecord> hits(rays.size());
    trace.place(rays.data(), rays.size() * sizeof(gpu::Ray));
    trace.place(hits.data(), hits.size() * sizeof(gpu::HitRecord));
    std::visit(
        [&](auto kernels) {
            kernels.query = query;
            const MemoryTrace::Scope scope(trace);
            for (std::size_t i = 0; i < rays.size(); ++i) {
                trace.read(MemoryKind::State, &rays[i], sizeof(gpu::Ray));  // the ray, read once
                hits[i] = kernels.rtTrace(rays[i]);
                trace.write(MemoryKind::Output, &hits[i], bytes::kOutput);
            }
        },
        structure.cpuKernels());
    return cache;
}

CacheSimulator multipassCacheReplay(const Structure& structure, const std::vector<gpu::Ray>& rays,
                                    const MultipassOptions& options, std::uint32_t query, std::uint64_t batchRays,
                                    const CacheConfig& config) {
    if (options.deviceControl)
        throw Error("cache.simulate replays Purcell's multipass, whose passes walk the whole stream through the stencil "
                    "(strategy.control = host), not the device-controlled one's compacted lists");
    CacheSimulator cache(config);
    MemoryTrace trace(cache);
    placeStructure(trace, structure);
    simulateMultipass(structure, rays, options, query, batchRays, &trace);
    return cache;
}

const std::vector<KeySpec>& cacheKeys() {
    static const std::vector<KeySpec> keys = [] {
        const std::vector<std::string> asked = {"strategy.type=branching|multipass", "cache.simulate=true"};
        std::vector<KeySpec> k = {
            {"cache.simulate", ValueType::Bool, "branching and multipass (host control): replay the run's memory references on the CPU through a texture cache, as Purcell et al. 2002 §4.1 did for Fig. 9 (one reference at a time, as by a single-pixel-wide pipeline), and write the cache_* columns", false, false, -1e300, 1e300, {}, {"strategy.type=branching|multipass"}},
            {"cache.size_bytes", ValueType::Int, "the cache's size (Purcell: 64 KB); it holds size / (line x ways) whole sets", std::int64_t(65536), false, 1, 1073741824.0, {}, asked},
            {"cache.line_bytes", ValueType::Int, "its line (Purcell: 48 bytes, four float RGB or three float RGBA texels)", std::int64_t(48), false, 1, 65536, {}, asked},
            {"cache.ways", ValueType::Int, "lines per set, the least recently used replaced (Purcell: 1, direct-mapped)", std::int64_t(1), false, 1, 1024, {}, asked},
        };
        for (KeySpec& key : k) key.since = 16;
        return k;
    }();
    return keys;
}

namespace {

// cache.simulate's columns (results schema 16), declared once, here, where they are written: the
// cache, the traffic ratio over all data, and per read data type its ratio and line hit rate.
struct CacheColumns {
    using K = ColumnKind;
    ColumnGroup group;
    Column<std::uint64_t> capacity = group.add<std::uint64_t>(
        {"cache_capacity_bytes", K::Exact, "bytes", "cache.simulate: the bytes the cache holds, sets x ways x line (64 KB of 48-byte lines: 65,520)", 0.0, false, {"cache.simulate=true"}, 16});
    Column<double> ratioTotal = group.add<double>(
        {"cache_ratio_total", K::Exact, "fraction", "cache.simulate: memory traffic with the cache / without it, all data types (Purcell 2002 Fig. 9's bar: a missed line costs the whole line; writes cost their bytes either way)", 0.0, false, {"cache.simulate=true"}, 16});
    struct ByKind {
        Column<double> ratio, hitRate;
    };
    std::vector<ByKind> byKind = [this] {
        std::vector<ByKind> kinds;
        for (const MemoryKind kind : kReadKinds) {
            const std::string name = memoryKindName(kind);
            const std::string without = kind == MemoryKind::Cells ? "bytes_voxel or bytes_node" : "bytes_" + name;
            kinds.push_back(
                {group.add<double>({"cache_ratio_" + name, K::Exact, "fraction", "cache.simulate: traffic of " + name + " data with the cache / without it (" + without + ")", 0.0, false, {"cache.simulate=true"}, 16}),
                 group.add<double>({"cache_hit_rate_" + name, K::Exact, "fraction", "cache.simulate: of the cache lines the " + name + " reads touch, the fraction found in the cache (empty: no reads)", 0.0, false, {"cache.simulate=true"}, 16})});
        }
        return kinds;
    }();
};

const CacheColumns& cacheColumnsDeclared() {
    static const CacheColumns columns;
    return columns;
}

}  // namespace

const std::vector<ColumnSpec>& cacheColumns() { return cacheColumnsDeclared().group.specs(); }

std::optional<CacheConfig> cacheConfig(const RunConfig& run) {
    if (!run.has("cache.simulate") || !run.getBool("cache.simulate")) return std::nullopt;
    CacheConfig c;
    c.sizeBytes = std::uint64_t(run.getInt("cache.size_bytes"));
    c.lineBytes = std::uint64_t(run.getInt("cache.line_bytes"));
    c.ways = std::uint64_t(run.getInt("cache.ways"));
    return c;
}

std::string writeCacheColumns(const CacheSimulator& cache, const Bandwidth& accounted, Row& row) {
    std::string differs;
    std::uint64_t with = 0, without = 0;
    for (int k = 0; k < kMemoryKinds; ++k) {
        const MemoryKind kind = static_cast<MemoryKind>(k);
        const CacheKindStats& s = cache.stats(kind);
        if (s.bytesWithout() != accountedBytes(accounted, kind))
            differs += std::string(differs.empty() ? "" : "; ") + memoryKindName(kind) + " " +
                       std::to_string(s.bytesWithout()) + " bytes in the cache replay, " +
                       std::to_string(accountedBytes(accounted, kind)) + " accounted";
        with += cache.bytesWith(kind);
        without += s.bytesWithout();
    }
    const CacheColumns& c = cacheColumnsDeclared();
    put(row, c.capacity, cache.capacityBytes());
    put(row, c.ratioTotal, without ? double(with) / double(without) : 1.0);
    for (std::size_t k = 0; k < std::size(kReadKinds); ++k) {
        const MemoryKind kind = kReadKinds[k];
        const CacheKindStats& s = cache.stats(kind);
        if (s.bytesWithout()) put(row, c.byKind[k].ratio, double(cache.bytesWith(kind)) / double(s.bytesWithout()));
        if (s.lineLookups) put(row, c.byKind[k].hitRate, double(s.lineHits) / double(s.lineLookups));
    }
    return differs.empty() ? "" : "the cache replay's bytes differ from the bandwidth accounting's: " + differs;
}

}  // namespace rtbench
