#include "cache_simulator.h"

#include <algorithm>

#include "core/error.h"

namespace rtbench {

const char* memoryKindName(MemoryKind kind) {
    switch (kind) {
        case MemoryKind::Stencil:
            return "stencil";
        case MemoryKind::State:
            return "state";
        case MemoryKind::Stack:
            return "stack";
        case MemoryKind::Cells:
            return "cells";
        case MemoryKind::TriangleList:
            return "triangle_list";
        case MemoryKind::Vertices:
            return "vertices";
        case MemoryKind::Output:
            return "output";
    }
    return "?";
}

CacheSimulator::CacheSimulator(const CacheConfig& config) : config_(config) {
    if (!config.sizeBytes || !config.lineBytes || !config.ways)
        throw Error("cache: size, line and ways must each be at least 1");
    sets_ = config.sizeBytes / (config.lineBytes * config.ways);
    if (!sets_)
        throw Error("cache: " + std::to_string(config.sizeBytes) + " bytes hold no set of " + std::to_string(config.ways) +
                    " lines of " + std::to_string(config.lineBytes) + " bytes");
    tags_.assign(sets_ * config.ways, 0);
}

std::size_t CacheSimulator::setOf(std::uint64_t line) const {
    // Sets by the line number modulo their count (not a power of two with 48-byte lines).
    return std::size_t((line % sets_) * config_.ways);
}

bool CacheSimulator::lookup(std::uint64_t line) {
    const auto set = tags_.begin() + std::ptrdiff_t(setOf(line));
    const auto end = set + std::ptrdiff_t(config_.ways);
    const std::uint64_t tag = line + 1;
    auto found = std::find(set, end, tag);
    const bool hit = found != end;
    if (!hit) found = end - 1;  // the least recently used way (or an empty one) goes
    std::rotate(set, found, found + 1);  // to the front
    *set = tag;
    return hit;
}

void CacheSimulator::read(MemoryKind kind, std::uint64_t address, std::uint64_t bytes) {
    if (!bytes) return;
    CacheKindStats& s = stats_[static_cast<int>(kind)];
    s.readBytes += bytes;
    for (std::uint64_t line = address / config_.lineBytes, last = (address + bytes - 1) / config_.lineBytes; line <= last;
         ++line) {
        ++s.lineLookups;
        s.lineHits += lookup(line);
    }
}

void CacheSimulator::write(MemoryKind kind, std::uint64_t address, std::uint64_t bytes) {
    if (!bytes) return;
    stats_[static_cast<int>(kind)].writeBytes += bytes;
    for (std::uint64_t line = address / config_.lineBytes, last = (address + bytes - 1) / config_.lineBytes; line <= last;
         ++line)
        if (written_.empty() || written_.back() != line) written_.push_back(line);
}

void CacheSimulator::endPass() {
    for (const std::uint64_t line : written_) {
        const auto set = tags_.begin() + std::ptrdiff_t(setOf(line));
        const auto end = set + std::ptrdiff_t(config_.ways);
        const auto found = std::find(set, end, line + 1);
        if (found == end) continue;
        std::rotate(found, found + 1, end);  // to the back, emptied: the next miss in the set takes it
        *(end - 1) = 0;
    }
    written_.clear();
}

std::uint64_t CacheSimulator::bytesWith(MemoryKind kind) const {
    const CacheKindStats& s = stats(kind);
    return (s.lineLookups - s.lineHits) * config_.lineBytes + s.writeBytes;
}

}  // namespace rtbench
