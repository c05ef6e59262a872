// The shared GLSL traversal of a structure compiled as C++: the macros that open it (GLSL's
// `out`/`inout` as references, the loop hooks logging the triangle-loop trips, `precise` as
// nothing since C++ is built without contraction), the members every such source expects besides
// the structure's buffers, and the CPU reference a structure gets from it: every hit record, the
// lane log and the multipass simulation run the kernels' very source.
//
// Use: in a namespace with `using namespace glm; using namespace rtbench::gpu;`,
//   #include "methods/shared_source_begin.h"
//   struct XKernels : KernelConstants { <buffers as pointers>; XParams params;
//   #include "../../kernels/ray_math.glsl"  ... the structure's .glsl files ... };
//   #include "methods/shared_source_end.h"
// then derive the structure from SharedSourceStructure<XKernels>.
#pragma once
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cstdint>
#include <cstring>
#include <vector>

#include "methods/multipass/multipass_simulator.h"
#include "methods/structure.h"

namespace rtbench {

// The specialization constants of the kernels, and the loop log of RT_ON_OUTER / RT_ON_INNER.
struct KernelConstants {
    std::uint32_t traverseStepsPerPass = 1;
    std::uint32_t intersectionsPerPass = 1;
    std::uint32_t suppressFinishedReads = 0;
    std::uint32_t triangleTest = gpu::kTriangleTestMollerTrumbore;
    std::uint32_t vertexBits = 0;  // packed vertices on this lattice when != 0 (methods/triangle_store.h)
    float latticeOriginX = 0.0f, latticeOriginY = 0.0f, latticeOriginZ = 0.0f, latticeStep = 0.0f;
    std::vector<std::uint32_t>* loopLog = nullptr;  // when set: per outer iteration, the triangle-loop trips

    void setMultipass(const MultipassOptions& options) {
        traverseStepsPerPass = options.traverseStepsPerPass;
        intersectionsPerPass = options.intersectionsPerPass;
        suppressFinishedReads = options.suppressFinishedReads ? 1u : 0u;
    }
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

template <class Kernels>
class SharedSourceStructure : public Structure {
public:
    // The shared source over this structure's data.
    virtual Kernels kernels() const = 0;
    // ... with the constants every structure shares (the triangle test, the vertex lattice).
    Kernels configured() const {
        Kernels k = kernels();
        k.triangleTest = triangleTest();
        k.setLattice(vertexLattice());
        return k;
    }

    std::vector<std::uint8_t> params() const override {
        const auto p = kernels().params;
        std::vector<std::uint8_t> bytes(sizeof p);
        std::memcpy(bytes.data(), &p, sizeof p);
        return bytes;
    }
    std::vector<gpu::HitRecord> trace(const std::vector<gpu::Ray>& rays) const override { return traceAll(configured(), rays); }
    void traceLoops(const gpu::Ray& ray, std::vector<std::uint32_t>& loopLog) const override {
        Kernels k = configured();
        k.loopLog = &loopLog;
        k.rtTrace(ray);
    }
    MultipassResult simulateMultipass(const std::vector<gpu::Ray>& rays, const MultipassOptions& options) const override {
        Kernels k = configured();
        k.setMultipass(options);
        return rtbench::simulateMultipass(k, rays, options, multipassPassCap(options));
    }
};

}  // namespace rtbench
