#include "grid_structure.h"

#include <cstring>

#include "device/gpu_buffers.h"
#include "grid_reference.h"
#include "structures/shared_source.h"
#include "structures/cost_model.h"
#include "structures/triangle_store.h"
#include "core/error.h"

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

std::string num(double v, int significant = 6) { return formatNumber(v, significant); }

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
        row["grid_res_x"] = std::to_string(g.resolution[0]);
        row["grid_res_y"] = std::to_string(g.resolution[1]);
        row["grid_res_z"] = std::to_string(g.resolution[2]);
        row["grid_cells"] = std::to_string(g.cells);
        row["grid_empty_fraction"] = num(g.emptyFraction);
        row["grid_references"] = std::to_string(g.references);
        row["grid_refs_per_triangle"] = num(g.referencesPerTriangle);
        row["grid_max_refs_in_cell"] = std::to_string(g.maxReferencesInCell);
        row["grid_bytes"] = std::to_string(g.bytes);
        row["grid_voxel_margin"] = num(g.voxelMargin, 4);
        row["grid_build_ms"] = num(g.buildMs, 4);
    }

    void writeWorkColumns(double cellsPerRayMean, std::uint32_t cellsPerRayMax, std::uint64_t cellBytes,
                          Row& row) const override {
        row["voxels_per_ray_mean"] = num(cellsPerRayMean);
        row["voxels_per_ray_max"] = std::to_string(cellsPerRayMax);
        row["bytes_voxel"] = std::to_string(cellBytes);
    }

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
        using K = ColumnKind;
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
        t.columns = {
            {"grid_res_x", K::Exact, "cells", "grid resolution along x"},
            {"grid_res_y", K::Exact, "cells", "grid resolution along y"},
            {"grid_res_z", K::Exact, "cells", "grid resolution along z"},
            {"grid_cells", K::Exact, "cells", "voxels in the grid"},
            {"grid_empty_fraction", K::Exact, "fraction", "voxels with no triangle"},
            {"grid_references", K::Exact, "references", "(voxel, triangle) pairs"},
            {"grid_refs_per_triangle", K::Exact, "references", "references per triangle"},
            {"grid_max_refs_in_cell", K::Exact, "references", "largest voxel list"},
            {"grid_bytes", K::Exact, "bytes", "grid memory (offsets, lists, vertices)"},
            {"grid_voxel_margin", K::Exact, "scene units", "structure.conservative: how far beyond its box a voxel lists triangles (0: exact voxels)"},
            {"grid_build_ms", K::Timing, "ms", "CPU build time of the grid: wall time, the triangles binned in parallel on TBB's threads, as Embree builds its BVH"},
            {"voxels_per_ray_mean", K::Exact, "voxels", "voxels visited per ray, mean"},
            {"voxels_per_ray_max", K::Exact, "voxels", "voxels visited per ray, max"},
            {"bytes_voxel", K::Exact, "bytes", "voxel offsets read"},
        };
        t.build = buildGrid;
        return t;
    }();
    return type;
}

}  // namespace rtbench
