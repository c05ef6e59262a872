// The structure half of a method's seam. A structure (uniform grid, BVH, brute force) lives in
// its own folder, methods/<name>/: its build, its GPU layout (<name>_layout.h, shared by C++ and
// GLSL), its per-ray traversal in GLSL (structure.glsl, which the generic kernels of kernels/
// include: CMake compiles every kernel once per structure), its CPU reference (the same GLSL
// compiled as C++), its accounting and its config keys and columns. A strategy
// (methods/strategy.h) runs any structure through the Structure interface below; the runner knows
// neither by name: methods/registry.cpp lists them.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "device/gpu_buffers.h"
#include "kernels/gpu_layout.h"
#include "methods/multipass/multipass_schedule.h"
#include "plan/columns.h"
#include "plan/keys.h"
#include "structures/mesh.h"

namespace rtbench {

// One of the structure's device buffers, in binding order from gpu::kBindingStructure; the
// host data is owned by the structure.
using StructureBuffer = BufferData;


// Bytes the kernels move per event the traversal counts (the accounting's unit costs).
struct StructureCosts {
    std::uint64_t bytesPerCellVisit = 0;      // branching: per cell visited (grid: 2 offsets; BVH: a node)
    std::uint64_t bytesPerStructureRead = 0;  // multipass: per counted structure read
    std::uint64_t bytesPerListEntry = 0;      // per triangle tested: its index in a list (0: none)
    std::uint64_t traversalStateBytes = 0;    // multipass: the per-ray traversal state
    std::uint64_t stackBytes = 0;             // multipass: the part of it that is a node stack
    std::uint64_t bytesPerTriangle = sizeof(gpu::Triangle);  // per triangle tested: its vertices (packed: 20)
};

// The CPU reference's multipass run: hit records with per-ray counters, and the pass counts.
struct MultipassResult {
    std::vector<gpu::HitRecord> hits;
    MultipassCounts counts;
};

// What a build produced, ready for any strategy.
class Structure {
public:
    virtual ~Structure() = default;

    // Kernel names are "<kernelPrefix>_<kernel>" (CMakeLists.txt: RTBENCH_STRUCTURES).
    virtual std::string kernelPrefix() const = 0;
    virtual std::vector<StructureBuffer> buffers() const = 0;
    // The push constants after gpu::StreamParams (the structure's RtParams), as bytes.
    virtual std::vector<std::uint8_t> params() const = 0;
    virtual StructureCosts costs() const = 0;

    // CPU reference, running the kernels' own source: every hit record, bit for bit.
    virtual std::vector<gpu::HitRecord> trace(const std::vector<gpu::Ray>& rays) const = 0;
    // One ray's branching traversal, logging the triangle-loop trips of each outer-loop iteration
    // (one entry per voxel or node visited): what the kernel's subgroup ballots see.
    virtual void traceLoops(const gpu::Ray& ray, std::vector<std::uint32_t>& loopLog) const = 0;
    // The multipass passes on the CPU, with the strategy's scheduler.
    virtual MultipassResult simulateMultipass(const std::vector<gpu::Ray>& rays,
                                              const MultipassOptions& options) const = 0;
    // A cap on multipass passes no correct run reaches (a fault that stops progress fails).
    virtual std::uint64_t multipassPassCap(const MultipassOptions& options) const = 0;

    // The cost model (methods/cost_model.h): the cell or node visits plus triangle tests these
    // rays are predicted to take, from the structure's statistics alone, before any ray is traced.
    virtual double predictedWork(const std::vector<gpu::Ray>& rays) const = 0;

    // The structure's own columns (its statistics), and its words for per-ray work.
    virtual void writeColumns(Row& row) const = 0;
    // Per-ray cells visited under the structure's name ("voxels_per_ray_mean"...); none for brute force.
    virtual void writeWorkColumns(double cellsPerRayMean, std::uint32_t cellsPerRayMax,
                                  std::uint64_t cellBytes, Row& row) const = 0;

    // The ray-triangle test its kernels and CPU reference run (gpu::kTriangleTest*,
    // intersection.test): set by the runner after the build, read by the strategies.
    virtual void setTriangleTest(std::uint32_t test) { triangleTest_ = test; }
    std::uint32_t triangleTest() const { return triangleTest_; }
    // The lattice its vertex buffer is packed to (bits 0: float vertices; methods/triangle_store.h).
    virtual const VertexLattice& vertexLattice() const = 0;

    std::uint64_t memoryBytes = 0;  // everything the structure uploads
    double buildMs = 0.0;           // CPU build time

private:
    std::uint32_t triangleTest_ = gpu::kTriangleTestMollerTrumbore;
};

// A structure as the registry lists it: its structure.type value, keys, columns and builder.
struct StructureType {
    std::string name;  // the structure.type value
    std::string help;
    std::vector<KeySpec> keys;        // read only when structure.type is this name
    std::vector<ColumnSpec> columns;  // written only by its runs
    // Builds the structure for a scene and the rays it will trace; refuses (throws rtbench::Error
    // naming the size and the limit) before allocating what the device could not hold.
    std::unique_ptr<Structure> (*build)(const TriangleMesh& mesh, const std::vector<gpu::Ray>& rays, const RunConfig& run,
                                        const DeviceInfo& device);
};

}  // namespace rtbench
