// The structure half of a method's seam. A structure (uniform grid, BVH, brute force) lives in
// its own folder, structures/<name>/: its build, its GPU layout (<name>_layout.h, shared by C++ and
// GLSL), its per-ray traversal in GLSL (structure.glsl, which the generic kernels of kernels/
// include: CMake compiles every kernel once per structure), its CPU reference (the same GLSL
// compiled as C++), its accounting and its config keys and columns. A strategy
// (strategies/strategy.h) runs any structure through the Structure interface below; the runner knows
// neither by name: methods/registry.cpp lists them.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "device/gpu_buffers.h"
#include "kernels/gpu_layout.h"
#include "structures/structure_kernels.h"
#include "schema/column.h"
#include "schema/columns.h"
#include "schema/keys.h"
#include "scene/mesh.h"

namespace rtbench {

// A structure's per-ray work in its own words (voxels, nodes): the cells a ray visits, mean and
// max, and the bytes of cells read, three columns a structure adds to its group where it declares
// them (the runner writes them through Structure::walkColumns).
struct WalkColumns {
    // `cells`: the columns' prefix and unit ("voxels": voxels_per_ray_mean...); `visited`: what is
    // counted ("voxels visited per ray"); `bytes`: the byte column's name and meaning.
    WalkColumns(ColumnGroup& group, const std::string& cells, const std::string& visited, const std::string& bytesName,
                const std::string& bytesMeaning)
        : perRayMean(group.add<double>({cells + "_per_ray_mean", ColumnKind::Exact, cells, visited + ", mean"})),
          perRayMax(group.add<std::uint32_t>({cells + "_per_ray_max", ColumnKind::Exact, cells, visited + ", max"})),
          bytes(group.add<std::uint64_t>({bytesName, ColumnKind::Exact, "bytes", bytesMeaning})) {}
    void write(double cellsPerRayMean, std::uint32_t cellsPerRayMax, std::uint64_t cellBytes, Row& row) const {
        put(row, perRayMean, cellsPerRayMean);
        put(row, perRayMax, cellsPerRayMax);
        put(row, bytes, cellBytes);
    }
    Column<double> perRayMean;
    Column<std::uint32_t> perRayMax;
    Column<std::uint64_t> bytes;
};

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

// Bounds on one ray's walk, from the structure's statistics: what a strategy caps its passes by.
struct WalkBounds {
    std::uint64_t maxCellsPerRay = 1;       // cells (voxels, nodes and leaves) one ray visits at most
    std::uint64_t maxTrianglesPerCell = 0;  // triangles one cell lists at most
};

// Purcell Table 1's per-event compute (methods/instructions): the kernel functions one traversal
// event runs, and which per-ray counter counts the event (cells visited, or traversal steps).
struct StepFunctions {
    std::vector<std::string> names;  // GLSL function names (none: no traversal, brute force)
    bool perCellVisited = false;
};

// What a build produced, ready for any strategy.
// The arithmetic every kernel of a run and its CPU reference share.
struct KernelArithmetic {
    std::uint32_t triangleTest = gpu::kTriangleTestMollerTrumbore;  // gpu::kTriangleTest*: intersection.test
    std::uint32_t division = gpu::kDivisionDouble;  // gpu::kDivision*: intersection.division (the same bits either way)
};

class Structure {
public:
    virtual ~Structure() = default;

    // Kernel names are "<kernelPrefix>_<kernel>" (CMakeLists.txt: RTBENCH_STRUCTURES).
    virtual std::string kernelPrefix() const = 0;
    virtual std::vector<StructureBuffer> buffers() const = 0;
    // The push constants after gpu::StreamParams (the structure's RtParams), as bytes.
    virtual std::vector<std::uint8_t> params() const = 0;
    virtual StructureCosts costs() const = 0;

    // The kernels' own source compiled as C++ over this structure's data, configured as its
    // kernels are (triangle test, vertex lattice; closest-hit query): what the strategies' CPU
    // models run (std::visit).
    virtual StructureKernels cpuKernels() const = 0;
    // CPU reference: every ray's hit record for the query (gpu::kQuery*), bit for bit the kernels'.
    std::vector<gpu::HitRecord> trace(const std::vector<gpu::Ray>& rays, std::uint32_t query = gpu::kQueryClosest) const;
    virtual WalkBounds walkBounds() const = 0;
    virtual StepFunctions stepFunctions() const { return {}; }

    // The cost model (structures/cost_model.h): the cell or node visits plus triangle tests these
    // rays are predicted to take, from the structure's statistics alone, before any ray is traced;
    // negative where the structure's traversal is not rtbench's to model (the driver's).
    virtual double predictedWork(const std::vector<gpu::Ray>& rays) const = 0;

    // The structure's own columns (its statistics), and its words for per-ray work.
    virtual void writeColumns(Row& row) const = 0;
    // Per-ray cells visited under the structure's name ("voxels_per_ray_mean"...); none for brute force.
    virtual const WalkColumns* walkColumns() const { return nullptr; }

    // The arithmetic its kernels and CPU reference run (KernelArithmetic): set by the runner after
    // the build, read by the strategies. A structure that wraps another passes it on.
    virtual void setArithmetic(const KernelArithmetic& arithmetic) { arithmetic_ = arithmetic; }
    void setTriangleTest(std::uint32_t test) { setArithmetic({test, arithmetic_.division}); }
    std::uint32_t triangleTest() const { return arithmetic_.triangleTest; }
    std::uint32_t division() const { return arithmetic_.division; }
    // The lattice its vertex buffer is packed to (bits 0: float vertices; structures/triangle_store.h).
    virtual const VertexLattice& vertexLattice() const = 0;

    // A structure the device builds (the driver's: methods/ray_query) builds it here, after the
    // CPU build and before any strategy runs; the others have nothing to do.
    virtual void buildOnDevice(VulkanContext&) {}

    std::uint64_t memoryBytes = 0;  // everything the structure uploads
    double buildMs = 0.0;           // build time (CPU; the driver's: its builds on the device)

private:
    KernelArithmetic arithmetic_;
};

// A structure as the registry lists it: its structure.type value, keys, columns and builder.
struct StructureType {
    std::string name;  // the structure.type value
    std::string help;
    std::vector<KeySpec> keys;        // read only when structure.type is this name
    std::vector<ColumnSpec> columns;  // written only by its runs
    std::string onlyStrategy;         // the one strategy.type that can trace it ("": any)
    bool autoCandidate = true;        // built and predicted by structure.type = auto
    // Builds the structure for a scene and the rays it will trace; refuses (throws rtbench::Error
    // naming the size and the limit) before allocating what the device could not hold.
    std::unique_ptr<Structure> (*build)(const TriangleMesh& mesh, const std::vector<gpu::Ray>& rays, const RunConfig& run,
                                        const DeviceInfo& device);
};

// The specialization constants a kernel of this structure takes (workgroup size, the triangle
// test, the vertex lattice, the query) with the strategy's own `constants`, instrumented.
KernelSpec structureKernelSpec(const Structure& structure, unsigned workgroupSize, std::uint32_t query,
                               std::vector<SpecializationConstant> constants);

}  // namespace rtbench
