#include "grid_structure.h"

#include <cstring>

#include "device/gpu_buffers.h"
#include "grid_reference.h"
#include "structures/shared_source.h"
#include "structures/cost_model.h"
#include "structures/triangle_store.h"
#include "core/error.h"
#include "schema/column.h"

namespace rtbench {

std::vector<BufferSize> gridBufferSizes(const std::array<unsigned, 3>& resolution, std::uint64_t references,
                                        std::uint64_t triangles, const VertexLattice& lattice) {
    const std::uint64_t cells = std::uint64_t(resolution[0]) * resolution[1] * resolution[2];
    const std::string res = std::to_string(resolution[0]) + "x" + std::to_string(resolution[1]) + "x" +
                            std::to_string(resolution[2]);
    return {{"grid cell offset (" + res + " = " + std::to_string(cells) + " cells)", (cells + 1) * 4},
            {"grid triangle list (" + std::to_string(references) + " references)", references * 4},
            {"triangle vertex (" + std::to_string(triangles) + " triangles)", triangles * triangleVertexBytes(lattice)}};
}

namespace {

GridResolutionRule resolutionRule(const RunConfig& run) {
    GridResolutionRule rule;
    if (run.has("structure.resolution")) {
        rule.kind = GridResolutionRule::Kind::Explicit;
        const auto r = run.getVec3("structure.resolution");
        rule.resolution = {unsigned(r[0]), unsigned(r[1]), unsigned(r[2])};
    } else if (run.has("structure.cells_per_triangle")) {
        rule.kind = GridResolutionRule::Kind::Density;
        rule.cellsPerTriangle = run.getFloat("structure.cells_per_triangle");
    } else {
        rule.kind = GridResolutionRule::Kind::MinDim;
        rule.minDim = unsigned(run.getInt("structure.min_dim"));
    }
    return rule;
}

// The grid's columns, each declared once, here, where its value is written.
struct GridColumns {
    using K = ColumnKind;
    ColumnGroup group;
    Column<unsigned> resX = group.add<unsigned>({"grid_res_x", K::Exact, "cells", "grid resolution along x"});
    Column<unsigned> resY = group.add<unsigned>({"grid_res_y", K::Exact, "cells", "grid resolution along y"});
    Column<unsigned> resZ = group.add<unsigned>({"grid_res_z", K::Exact, "cells", "grid resolution along z"});
    Column<std::uint64_t> cells = group.add<std::uint64_t>({"grid_cells", K::Exact, "cells", "voxels in the grid"});
    Column<double> emptyFraction = group.add<double>({"grid_empty_fraction", K::Exact, "fraction", "voxels with no triangle"});
    Column<std::uint64_t> references = group.add<std::uint64_t>({"grid_references", K::Exact, "references", "(voxel, triangle) pairs"});
    Column<double> referencesPerTriangle = group.add<double>({"grid_refs_per_triangle", K::Exact, "references", "references per triangle"});
    Column<std::uint32_t> maxReferencesInCell = group.add<std::uint32_t>({"grid_max_refs_in_cell", K::Exact, "references", "largest voxel list"});
    Column<std::uint64_t> bytes = group.add<std::uint64_t>({"grid_bytes", K::Exact, "bytes", "grid memory (offsets, lists, vertices)"});
    Column<double> voxelMargin = group.add<double>(
        {"grid_voxel_margin", K::Exact, "scene units", "structure.conservative: how far beyond its box a voxel lists triangles (0: exact voxels)"}, 4);
    Column<double> buildMs = group.add<double>(
        {"grid_build_ms", K::Timing, "ms", "CPU build time of the grid: wall time, the triangles binned in parallel on TBB's threads, as Embree builds its BVH"}, 4);
    WalkColumns walk{group, "voxels", "voxels visited per ray", "bytes_voxel", "voxel offsets read"};
};

const GridColumns& gridColumns() {
    static const GridColumns columns;
    return columns;
}

class GridStructure final : public SharedSourceStructure<gridref::GridKernels> {
public:
    explicit GridStructure(UniformGrid grid) : grid_(std::move(grid)), vertices_(grid_.triangles, grid_.lattice) {
        memoryBytes = grid_.stats.bytes;
        buildMs = grid_.stats.buildMs;
    }

    std::string kernelPrefix() const override { return "uniform_grid"; }

    std::vector<StructureBuffer> buffers() const override {
        const std::vector<BufferSize> sizes =
            gridBufferSizes(grid_.stats.resolution, grid_.triangleList.size(), grid_.triangles.size(), grid_.lattice);
        return {{sizes[0].what, sizes[0].bytes, grid_.cellOffsets.data()},
                {sizes[1].what, sizes[1].bytes, grid_.triangleList.data()},
                vertices_.buffer()};
    }

    StructureCosts costs() const override {
        StructureCosts c;
        c.bytesPerCellVisit = 2 * 4;    // a voxel entered reads its two cell offsets
        c.bytesPerStructureRead = 4;    // one cell offset
        c.bytesPerListEntry = 4;        // one triangle id of a voxel's list
        c.traversalStateBytes = sizeof(gpu::GridTraversalState);
        c.bytesPerTriangle = triangleVertexBytes(vertexLattice());
        return c;
    }

    const VertexLattice& vertexLattice() const override { return vertices_.lattice(); }

    gridref::GridKernels kernels() const override {
        gridref::GridKernels k = gridKernels(grid_);
        vertices_.bind(k);
        return k;
    }

    // A ray visits at most resX + resY + resZ voxels; a voxel lists at most maxReferencesInCell.
    StepFunctions stepFunctions() const override { return {{"rtDdaStep"}, /*perCellVisited=*/false}; }  // a DDA step
    WalkBounds walkBounds() const override {
        const auto& r = grid_.stats.resolution;
        return {std::uint64_t(r[0]) + r[1] + r[2], grid_.stats.maxReferencesInCell};
    }

    // Every voxel has the same surface area: a line through the box crosses cells x A_cell / A_box
    // voxels on average, each listing references / cells triangles.
    double predictedWork(const std::vector<gpu::Ray>& rays) const override {
        const glm::vec3 lo(grid_.params.boundsMin), hi(grid_.params.boundsMax), cell(grid_.params.cellSize);
        const double cells = double(grid_.stats.cells);
        const double voxelsPerRay = cells * surfaceArea(glm::vec3(0.0f), cell) / surfaceArea(lo, hi);
        const double perRay = voxelsPerRay * (1.0 + double(grid_.stats.references) / cells);
        return double(raysEnteringBox(rays, lo, hi)) * perRay;
    }

    void writeColumns(Row& row) const override {
        const GridStats& g = grid_.stats;
        const GridColumns& c = gridColumns();
        put(row, c.resX, g.resolution[0]);
        put(row, c.resY, g.resolution[1]);
        put(row, c.resZ, g.resolution[2]);
        put(row, c.cells, g.cells);
        put(row, c.emptyFraction, g.emptyFraction);
        put(row, c.references, g.references);
        put(row, c.referencesPerTriangle, g.referencesPerTriangle);
        put(row, c.maxReferencesInCell, g.maxReferencesInCell);
        put(row, c.bytes, g.bytes);
        put(row, c.voxelMargin, g.voxelMargin);
        put(row, c.buildMs, g.buildMs);
    }

    const WalkColumns* walkColumns() const override { return &gridColumns().walk; }

private:
    UniformGrid grid_;
    TriangleStore vertices_;  // over grid_.triangles
};

std::unique_ptr<Structure> buildGrid(const TriangleMesh& mesh, const std::vector<gpu::Ray>& rays, const RunConfig& run,
                                     const DeviceInfo& device) {
    // Refuse before building what the device cannot hold (the cell offsets and vertices; the
    // triangle list, known only once built, is checked with every other buffer at upload).
    const GridResolutionRule rule = resolutionRule(run);
    const auto resolution = chooseGridResolution(mesh.bounds(), mesh.triangles.size(), rule);
    refuseOversizedBuffers(device, gridBufferSizes(resolution, 0, mesh.triangles.size(), mesh.lattice));
    const float margin =
        run.getBool("structure.conservative") ? conservativeVoxelMargin(gridBounds(mesh.bounds()), rays, resolution) : 0.0f;
    return gridStructure(buildUniformGrid(mesh, rule, 1ull << 31, margin));
}

}  // namespace

std::unique_ptr<Structure> gridStructure(UniformGrid grid) { return std::make_unique<GridStructure>(std::move(grid)); }

const StructureType& gridStructureType() {
    static const StructureType type = [] {
        StructureType t;
        t.name = "uniform_grid";
        t.help = "uniform grid (Purcell et al. 2002 Fig. 4), CGAL's exact triangle-box membership";
        const std::string rule = "grid resolution";
        t.keys = {
            {"structure.min_dim", ValueType::Int, "Purcell's heuristic: cells along the smallest extent (default 64 when no rule is given)", {}, false, 1, 2048, {}, {}, {}, rule, std::int64_t(64)},
            {"structure.resolution", ValueType::Int3, "explicit cells per axis [x, y, z]", {}, false, 1, 4096, {}, {}, {}, rule},
            {"structure.cells_per_triangle", ValueType::Float, "density rule: about this many cubic cells per triangle", {}, false, 1e-3, 1e3, {}, {}, {}, rule},
            {"structure.conservative", ValueType::Bool, "conservative traversal: each voxel also lists the triangles within a margin of it that bounds the DDA's rounding (structures/uniform_grid/uniform_grid.h), so a ray through an edge or a corner, or far from the origin, loses no triangle", false},
        };
        t.columns = gridColumns().group.specs();
        t.build = buildGrid;
        return t;
    }();
    return type;
}

}  // namespace rtbench
