// A texture cache as Purcell et al. 2002 §4.1 simulated one for Fig. 9: "a 64KB direct-mapped
// texture cache with a 48-byte line size", fed one memory reference at a time, as by "a single
// pixel wide graphics pipeline". Size, line and associativity are configurable (cache.* keys).
// Reads go through the cache: each line a read touches is looked up, and a miss fetches the
// whole line. Writes (stencil, state, hit records: the framebuffer's) bypass it: they cost their
// bytes with or without the cache and bring nothing in. A multipass pass reads its state from
// one texture and renders the new state to another (ping-pong), so nothing a pass reads changes
// during it, and what it wrote is new data to the next: endPass() drops the lines written.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

namespace rtbench {

// The data types of Purcell's Figs. 8-9, split as methods/accounting.h's Bandwidth is.
enum class MemoryKind : int { Stencil, State, Stack, Cells, TriangleList, Vertices, Output };
constexpr int kMemoryKinds = 7;
// Its runs.csv word, as in the bytes_<kind> columns: "stencil", "state", ..., "triangle_list".
const char* memoryKindName(MemoryKind kind);

struct CacheConfig {
    std::uint64_t sizeBytes = 65536;  // Purcell: 64 KB (48-byte lines: 1,365 of them, 65,520 bytes)
    std::uint64_t lineBytes = 48;     // Purcell: four float RGB texels or three RGBA ones
    std::uint64_t ways = 1;           // 1: direct-mapped (Purcell); lines per set, least recently used out
};

struct CacheKindStats {
    std::uint64_t readBytes = 0;   // bytes the reads asked for
    std::uint64_t writeBytes = 0;  // bytes written (never cached)
    std::uint64_t lineLookups = 0;  // lines the reads touched, one lookup each
    std::uint64_t lineHits = 0;

    std::uint64_t bytesWithout() const { return readBytes + writeBytes; }
};

class CacheSimulator {
public:
    // Throws rtbench::Error when the cache holds no whole set (size < line x ways) or a value is 0.
    explicit CacheSimulator(const CacheConfig& config);

    void read(MemoryKind kind, std::uint64_t address, std::uint64_t bytes);
    void write(MemoryKind kind, std::uint64_t address, std::uint64_t bytes);
    // The end of a rendering pass: every line written since the last one leaves the cache (its
    // copy there is stale), the others stay in their order.
    void endPass();

    const CacheConfig& config() const { return config_; }
    std::uint64_t sets() const { return sets_; }
    // The bytes the cache holds: sets x ways x line (Purcell's 64 KB of 48-byte lines: 65,520).
    std::uint64_t capacityBytes() const { return sets_ * config_.ways * config_.lineBytes; }
    const CacheKindStats& stats(MemoryKind kind) const { return stats_[static_cast<int>(kind)]; }
    // Memory traffic with the cache: a line per missed lookup, plus the writes.
    std::uint64_t bytesWith(MemoryKind kind) const;

private:
    bool lookup(std::uint64_t line);  // true on a hit; a miss brings the line in
    std::size_t setOf(std::uint64_t line) const;  // index in tags_ of the first way of the line's set

    CacheConfig config_;
    std::uint64_t sets_;
    // ways_ entries per set, most recently used first; a line number + 1 (0: empty).
    std::vector<std::uint64_t> tags_;
    std::array<CacheKindStats, kMemoryKinds> stats_{};
    std::vector<std::uint64_t> written_;  // lines written this pass
};

}  // namespace rtbench
