// The memory reads of the kernels' source compiled as C++ (structures/shared_kernels.h), for the
// texture-cache simulation of Purcell et al. 2002 §4.1 and Fig. 9: a structure's buffers are
// TracedArrays, which report every element the source reads to the calling thread's current
// MemoryTrace (none, as in every other use: a plain array read). The trace places the host
// buffers at device addresses and hands each access to the cache simulator.
#pragma once
#include <cstdint>
#include <map>

#include "methods/cache/cache_simulator.h"

namespace rtbench {

class MemoryTrace {
public:
    explicit MemoryTrace(CacheSimulator& cache) : cache_(cache) {}

    // Gives [data, data + bytes) the next device addresses, from a boundary of both 256 bytes
    // (Vulkan's largest minStorageBufferOffsetAlignment) and the cache line (a texture starts a
    // line: Purcell's 48-byte line holds one triangle's three RGBA vertices); a host range placed
    // before that overlaps it (a freed batch's buffer) is forgotten. Nothing is placed for 0 bytes.
    void place(const void* data, std::uint64_t bytes);
    // An access of `bytes` at host address p (none for 0 bytes).
    void read(MemoryKind kind, const void* p, std::uint64_t bytes) {
        if (bytes) cache_.read(kind, address(p, bytes), bytes);
    }
    void write(MemoryKind kind, const void* p, std::uint64_t bytes) {
        if (bytes) cache_.write(kind, address(p, bytes), bytes);
    }
    void endPass() { cache_.endPass(); }

    // Makes `trace` the calling thread's current trace while the Scope lives.
    class Scope {
    public:
        explicit Scope(MemoryTrace& trace) : previous_(current_) { current_ = &trace; }
        ~Scope() { current_ = previous_; }
        Scope(const Scope&) = delete;
        Scope& operator=(const Scope&) = delete;

    private:
        MemoryTrace* previous_;
    };
    static MemoryTrace* current() { return current_; }

private:
    // The device address of host range [p, p + bytes); throws rtbench::Error outside every placed buffer.
    std::uint64_t address(const void* p, std::uint64_t bytes) const;

    struct Region {
        std::uint64_t bytes;
        std::uint64_t device;
    };
    CacheSimulator& cache_;
    std::map<std::uintptr_t, Region> regions_;  // by host address
    std::uint64_t next_ = 0;
    static constinit inline thread_local MemoryTrace* current_ = nullptr;
};

// A kernel buffer of the shared source compiled as C++: element reads, reported as `kKind` to the
// thread's current trace when there is one.
template <class T, MemoryKind kKind>
struct TracedArray {
    const T* data = nullptr;

    TracedArray& operator=(const T* p) {
        data = p;
        return *this;
    }
    const T& operator[](std::uint32_t i) const {
        if (MemoryTrace* trace = MemoryTrace::current()) trace->read(kKind, data + i, sizeof(T));
        return data[i];
    }
};

}  // namespace rtbench
