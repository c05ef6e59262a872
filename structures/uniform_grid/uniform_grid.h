// Uniform grid over a triangle mesh, laid out as in Purcell et al. 2002 Fig. 4: per voxel an
// offset into a triangle-index list, the list, and the triangles' vertices.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "grid_layout.h"
#include "scene/mesh.h"
#include "scene/scene_limits.h"

namespace rtbench {

// How the grid resolution is chosen. Exactly one rule applies.
struct GridResolutionRule {
    enum class Kind { MinDim, Explicit, Density };
    Kind kind = Kind::MinDim;
    // A flat axis (zero extent) always gets one cell; the rules below apply to the others.
    // MinDim (Purcell): the smallest non-zero extent of the scene box gets minDim cells, the
    // other axes proportionally (rounded to nearest, at least 1), so voxels stay near cubic.
    unsigned minDim = 64;
    // Explicit: cells per axis.
    std::array<unsigned, 3> resolution{64, 64, 64};
    // Density (cube-root rule): about cellsPerTriangle * triangles cubic cells in the box; in a
    // flat box square cells over its area (one zero extent) or cells along its length (two).
    double cellsPerTriangle = 1.0;
};

// The grid's box: the mesh bounds, with a flat (zero) extent widened to 1e-4 of the largest
// extent so every axis has a positive size. Throws rtbench::Error for a box whose largest extent
// is below kMinSceneExtent (a point, a subnormal box) or not finite.
Bounds3 gridBounds(const Bounds3& meshBounds);

// Cells per axis for the scene's own bounds (not the widened grid box: a zero extent marks a flat
// axis) and triangle count. Each axis gets at least 1. Throws rtbench::Error, naming the
// resolution, when an axis would get more cells than the kernels' int indices hold.
std::array<unsigned, 3> chooseGridResolution(const Bounds3& sceneBounds, std::size_t triangleCount,
                                             const GridResolutionRule& rule);

struct GridStats {
    std::array<unsigned, 3> resolution{};
    std::uint64_t cells = 0;
    double emptyFraction = 0.0;
    std::uint64_t references = 0;  // triangle ids over all voxels
    double referencesPerTriangle = 0.0;
    std::uint32_t maxReferencesInCell = 0;
    std::uint64_t bytes = 0;  // cell offsets + triangle list + triangle vertices
    double buildMs = 0.0;
    float voxelMargin = 0.0f;  // scene units; 0: exact voxels
    // Candidate voxels tested, and those the float filters left to CGAL's exact test.
    std::uint64_t voxelTests = 0, exactTests = 0;
};

struct VoxelBox {
    glm::dvec3 min, max;
};

struct UniformGrid {
    gpu::GridParams params{};               // box, cell size, resolution (w: ray count, set later)
    std::vector<std::uint32_t> cellOffsets;  // cells + 1 entries; voxel c lists [off[c], off[c+1])
    std::vector<std::uint32_t> triangleList;
    std::vector<gpu::Triangle> triangles;    // vertices per triangle (Purcell's vertex textures)
    VertexLattice lattice;                   // the mesh's: bits != 0, the device stores them packed
    GridStats stats;

    std::uint64_t cellCount() const { return cellOffsets.empty() ? 0 : cellOffsets.size() - 1; }
    // Box of voxel (x, y, z), computed as the DDA computes boundaries: min + i * cellSize.
    // Voxel (x, y, z) as the walk sees it: boundsMin + [c, c + 1] * cellSize, exactly (in double);
    // the last voxel of an axis reaches boundsMax.
    VoxelBox voxelBounds(unsigned x, unsigned y, unsigned z) const;
};

// Builds the grid (grid_cells.h): each triangle's bounding box gives a candidate cell range
// (widened by one cell where it lies on a boundary), and the exact triangle-box predicate decides
// membership for every candidate (closed boxes: a triangle touching a voxel's face belongs to
// it): float filters where they are sure (voxel_block_filter.h, then triangle_box_filter.h),
// CGAL's exact test where not. Triangles are binned in parallel (TBB) and the lists are the same
// whatever the scheduling.
// Throws rtbench::Error when the scene is outside the range of scene/scene_limits.h or the
// cell count would exceed maxCells.
// voxelMargin > 0 makes the grid conservative: the box grows by the margin on every side, and a
// voxel lists every triangle within the margin of it (its box widened by the margin), so a walk
// whose rounding strays by less than the margin from the ray never misses a triangle the ray hits.
UniformGrid buildUniformGrid(const TriangleMesh& mesh, const GridResolutionRule& rule,
                             std::uint64_t maxCells = 1ull << 31, float voxelMargin = 0.0f);

// The margin that covers the DDA's rounding for these rays (structure.conservative). The walk runs
// in the grid's frame (origin at the box's min corner): every position it computes (the origin
// there, the entry point, a voxel boundary, a boundary distance stepped up to resX + resY + resZ
// times) is off by at most a few float ulps of the largest magnitude M in that frame, among the
// box's extent and the ray origins; (4 (resX + resY + resZ) + 16) ulp(M) bounds it.
float conservativeVoxelMargin(const Bounds3& gridBox, const std::vector<gpu::Ray>& rays,
                              const std::array<unsigned, 3>& resolution);

// The exact predicate used by the builder, exposed for tests.
// margin > 0 widens the box by it on every side first.
bool triangleOverlapsBox(const gpu::Triangle& triangle, const VoxelBox& box, float margin = 0.0f);

}  // namespace rtbench
