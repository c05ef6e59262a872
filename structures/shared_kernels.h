// The shared GLSL traversal of a structure compiled as C++ (structures/shared_source_begin.h): the
// members every such source expects besides the structure's buffers (the kernels'
// specialization constants and the loop log of RT_ON_OUTER / RT_ON_INNER), and the trace of a
// ray stream through it. Each structure's <name>_reference.h declares its XKernels over these;
// structures/structure_kernels.h lists them for the strategies' CPU models.
#pragma once
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cstdint>
#include <vector>

#include "kernels/gpu_layout.h"
#include "methods/cache/memory_trace.h"
#include "scene/mesh.h"

namespace rtbench {

// The specialization constants of the kernels, and the loop log of RT_ON_OUTER / RT_ON_INNER.
struct KernelConstants {
    std::uint32_t traverseStepsPerPass = 1;
    std::uint32_t intersectionsPerPass = 1;
    std::uint32_t suppressFinishedReads = 0;
    std::uint32_t triangleTest = gpu::kTriangleTestMollerTrumbore;
    std::uint32_t query = gpu::kQueryClosest;  // gpu::kQuery*: closest hit or any hit
    std::uint32_t nativeDivision = 0;  // the CPU's float division is IEEE's, correctly rounded, either way
    std::uint32_t division = gpu::kDivisionDouble;  // gpu::kDivision*: how rtDivide rounds exactly
    std::uint32_t vertexBits = 0;  // packed vertices on this lattice when != 0 (structures/triangle_store.h)
    float latticeOriginX = 0.0f, latticeOriginY = 0.0f, latticeOriginZ = 0.0f, latticeStep = 0.0f;
    std::vector<std::uint32_t>* loopLog = nullptr;  // when set: per outer iteration, the triangle-loop trips

    void setLattice(const VertexLattice& lattice) {
        vertexBits = lattice.bits;
        latticeOriginX = lattice.origin.x;
        latticeOriginY = lattice.origin.y;
        latticeOriginZ = lattice.origin.z;
        latticeStep = lattice.step;
    }
};

// Every ray through the shared rtTrace, in parallel; hits[i] is ray i's record.
template <class Kernels>
std::vector<gpu::HitRecord> traceAll(const Kernels& kernels, const std::vector<gpu::Ray>& rays) {
    std::vector<gpu::HitRecord> hits(rays.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), 1024), [&](const auto& range) {
        Kernels k = kernels;
        for (std::size_t i = range.begin(); i != range.end(); ++i) hits[i] = k.rtTrace(rays[i]);
    });
    return hits;
}

}  // namespace rtbench
