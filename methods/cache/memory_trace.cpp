#include "memory_trace.h"

#include <numeric>

#include "core/error.h"

namespace rtbench {

void MemoryTrace::place(const void* data, std::uint64_t bytes) {
    if (!bytes) return;
    const std::uintptr_t begin = reinterpret_cast<std::uintptr_t>(data), end = begin + bytes;
    // Forget what this range overlaps: the first region starting before its end, back to the
    // first that ends after its start.
    auto it = regions_.lower_bound(end);
    while (it != regions_.begin()) {
        auto before = std::prev(it);
        if (before->first + before->second.bytes <= begin) break;
        it = regions_.erase(before);
    }
    const std::uint64_t alignment = std::lcm<std::uint64_t>(256, cache_.config().lineBytes);
    next_ = (next_ + alignment - 1) / alignment * alignment;
    regions_[begin] = {bytes, next_};
    next_ += bytes;
}

std::uint64_t MemoryTrace::address(const void* p, std::uint64_t bytes) const {
    const std::uintptr_t at = reinterpret_cast<std::uintptr_t>(p);
    auto it = regions_.upper_bound(at);
    if (it != regions_.begin()) {
        --it;
        if (at + bytes <= it->first + it->second.bytes) return it->second.device + (at - it->first);
    }
    throw Error("memory trace: a read or write of " + std::to_string(bytes) +
                " bytes outside every buffer placed (a kernel buffer the trace was not given)");
}

}  // namespace rtbench
