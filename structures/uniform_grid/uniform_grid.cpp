#include "uniform_grid.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include <tbb/parallel_for.h>

#include "methods/triangle_store.h"
#include "triangle_box_filter.h"
#include "core/error.h"
#include "scene/scene_limits.h"

namespace rtbench {

namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

// Candidate cell range of [vmin, vmax] on one axis. The float cell computation may be off by one
// within rounding of a boundary, so a coordinate that close to one widens the range by a cell;
// the exact predicate then decides. Clamped with fmax/fmin, which also send a NaN to the grid's
// edge, so the range is always within [0, resolution - 1].
void candidateRange(float vmin, float vmax, float boxMin, float invCellSize, unsigned resolution,
                    int& lo, int& hi) {
    constexpr double kNear = 1e-4;  // in cells; rounding errors are ~1e-6 cells
    const double localMin = (double(vmin) - boxMin) * invCellSize;
    const double localMax = (double(vmax) - boxMin) * invCellSize;
    double cellMin = std::floor(localMin), cellMax = std::floor(localMax);
    if (localMin - cellMin < kNear) cellMin -= 1.0;
    if (cellMax + 1.0 - localMax < kNear) cellMax += 1.0;
    const double last = static_cast<double>(resolution) - 1.0;
    lo = static_cast<int>(std::fmin(std::fmax(cellMin, 0.0), last));
    hi = static_cast<int>(std::fmax(std::fmin(cellMax, last), 0.0));
}

std::string boxText(const glm::dvec3& e) {
    return formatFloat(e.x) + " x " + formatFloat(e.y) + " x " + formatFloat(e.z);
}

std::string resolutionText(const std::array<double, 3>& r) {
    char text[96];
    std::snprintf(text, sizeof text, "%.0fx%.0fx%.0f", r[0], r[1], r[2]);
    return text;
}
}  // namespace

Bounds3 gridBounds(const Bounds3& meshBounds) {
    if (meshBounds.empty()) throw Error("grid: the scene has no triangles");
    Bounds3 box = meshBounds;
    const glm::vec3 e = box.extent();
    const float largest = std::max({e.x, e.y, e.z});
    if (!(largest >= kMinSceneExtent))  // a point, a subnormal or a non-finite box
        throw Error("grid: the scene box is " + boxText(e) + ": " + sceneRangeText());
    for (int a = 0; a < 3; ++a) {
        if (e[a] > 0.0f) continue;
        const float pad = 0.5e-4f * largest;
        box.min[a] -= pad;
        box.max[a] += pad;
    }
    return box;
}

std::array<unsigned, 3> chooseGridResolution(const Bounds3& sceneBounds, std::size_t triangleCount,
                                             const GridResolutionRule& rule) {
    if (rule.kind == GridResolutionRule::Kind::Explicit)
        return {std::max(1u, rule.resolution[0]), std::max(1u, rule.resolution[1]), std::max(1u, rule.resolution[2])};
    // A zero extent is a flat axis: it gets one cell and the rules work on the other axes.
    const glm::dvec3 e(sceneBounds.extent());
    double smallest = std::numeric_limits<double>::infinity(), measure = 1.0;
    int dimensions = 0;
    for (int a = 0; a < 3; ++a)
        if (e[a] > 0.0) smallest = std::min(smallest, e[a]), measure *= e[a], ++dimensions;
    if (dimensions == 0) throw Error("grid: the scene box is a single point");
    std::array<double, 3> cells{1.0, 1.0, 1.0};
    if (rule.kind == GridResolutionRule::Kind::MinDim) {  // Purcell et al. 2002 §4.2
        for (int a = 0; a < 3; ++a)
            if (e[a] > 0.0) cells[a] = std::max(1.0, std::round(rule.minDim * e[a] / smallest));
    } else {  // cube-root rule (Cleary & Wyvill 1988): volume, or area or length of a flat box
        const double wanted = rule.cellsPerTriangle * static_cast<double>(triangleCount);
        const double perCell = measure / wanted;
        const double cellSize = dimensions == 3 ? std::cbrt(perCell) : dimensions == 2 ? std::sqrt(perCell) : perCell;
        for (int a = 0; a < 3; ++a)
            if (e[a] > 0.0) cells[a] = std::max(1.0, std::round(e[a] / cellSize));
    }
    // The kernels index cells with int: refuse what does not fit before converting.
    constexpr double kMaxCellsPerAxis = 2147483647.0;
    for (int a = 0; a < 3; ++a)
        if (!(cells[a] <= kMaxCellsPerAxis))
            throw Error("grid: resolution " + resolutionText(cells) + " has more than 2147483647 cells along " +
                        std::string(1, "xyz"[a]) + ", the most the kernels index (the scene box is " + boxText(e) + ")");
    return {unsigned(cells[0]), unsigned(cells[1]), unsigned(cells[2])};
}

VoxelBox UniformGrid::voxelBounds(unsigned x, unsigned y, unsigned z) const {
    const glm::uvec3 c(x, y, z);
    VoxelBox b;
    for (int a = 0; a < 3; ++a) {  // a 24-bit float times a cell index below 2^29, plus a float: exact in double
        b.min[a] = double(params.boundsMin[a]) + double(c[a]) * double(params.cellSize[a]);
        b.max[a] = double(params.boundsMin[a]) + double(c[a] + 1) * double(params.cellSize[a]);
        // The walk clamps to the last voxel, which therefore reaches the box's max even where
        // resolution x cellSize (cellSize rounded to float) falls short of it: 43 x fl(4/43) < 4.
        if (c[a] + 1 == params.resolution[a]) b.max[a] = std::max(b.max[a], double(params.boundsMax[a]));
    }
    return b;
}

namespace {

// The CGAL triangle of a grid triangle, and whether it is degenerate (a segment or a point).
Kernel::Triangle_3 cgalTriangle(const gpu::Triangle& t) {
    return Kernel::Triangle_3(Kernel::Point_3(t.v0.x, t.v0.y, t.v0.z), Kernel::Point_3(t.v1.x, t.v1.y, t.v1.z),
                              Kernel::Point_3(t.v2.x, t.v2.y, t.v2.z));
}

// CGAL's exact test of the closed triangle against the closed box.
bool exactOverlap(const Kernel::Triangle_3& triangle, bool degenerate, const CGAL::Bbox_3& bbox) {
    if (degenerate) {  // CGAL's triangle-box test requires a proper triangle
        const Kernel::Segment_3 s0(triangle[0], triangle[1]), s1(triangle[1], triangle[2]), s2(triangle[0], triangle[2]);
        if (s0.is_degenerate() && s1.is_degenerate()) return CGAL::do_intersect(bbox, triangle[0]);
        return (!s0.is_degenerate() && CGAL::do_intersect(bbox, s0)) || (!s1.is_degenerate() && CGAL::do_intersect(bbox, s1)) ||
               (!s2.is_degenerate() && CGAL::do_intersect(bbox, s2));
    }
    return CGAL::do_intersect(triangle, bbox);
}

// A voxel's box widened by the margin, as both tests see it.
CGAL::Bbox_3 widenedBox(const VoxelBox& box, float margin) {
    const double m = margin;
    return CGAL::Bbox_3(box.min.x - m, box.min.y - m, box.min.z - m, box.max.x + m, box.max.y + m, box.max.z + m);
}

// The grid's box (the scene's, widened by the margin), resolution and cell size.
gpu::GridParams gridFrame(const TriangleMesh& mesh, const GridResolutionRule& rule, std::uint64_t maxCells, float voxelMargin) {
    const Bounds3 sceneBounds = mesh.bounds();
    Bounds3 box = gridBounds(sceneBounds);
    box.min -= glm::vec3(voxelMargin);
    box.max += glm::vec3(voxelMargin);
    const std::array<unsigned, 3> res = chooseGridResolution(sceneBounds, mesh.triangles.size(), rule);
    const std::uint64_t cells = std::uint64_t(res[0]) * res[1] * res[2];
    if (cells > maxCells)
        throw Error("grid: resolution " + std::to_string(res[0]) + "x" + std::to_string(res[1]) + "x" + std::to_string(res[2]) +
                    " = " + std::to_string(cells) + " cells exceeds the limit of " + std::to_string(maxCells) + " cells");
    gpu::GridParams p{};
    p.boundsMin = glm::vec4(box.min, 0.0f);
    p.boundsMax = glm::vec4(box.max, 0.0f);
    for (int a = 0; a < 3; ++a) {
        p.cellSize[a] = box.extent()[a] / static_cast<float>(res[a]);
        p.invCellSize[a] = 1.0f / p.cellSize[a];
    }
    p.resolution = glm::uvec4(res[0], res[1], res[2], 0u);
    return p;
}

using CellPairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;  // (cell, triangle)

// Voxels tested, and those CGAL decided.
struct TestCounts {
    std::uint64_t voxels = 0, exact = 0;
};

// Appends triangle i's (cell, i) pairs: every voxel of its candidate range that it meets. The
// float filter decides where it is sure (triangle_box_filter.h); CGAL's exact test the rest, so
// the cells are the exact test's.
void binTriangle(const UniformGrid& grid, std::uint32_t i, float voxelMargin, CellPairs& pairs, TestCounts& counts) {
    const gpu::Triangle& t = grid.triangles[i];
    const gpu::GridParams& p = grid.params;
    glm::ivec3 lo, hi;
    for (int a = 0; a < 3; ++a) {
        const float vmin = std::min({t.v0[a], t.v1[a], t.v2[a]});
        const float vmax = std::max({t.v0[a], t.v1[a], t.v2[a]});
        candidateRange(vmin - voxelMargin, vmax + voxelMargin, p.boundsMin[a], p.invCellSize[a], p.resolution[a], lo[a], hi[a]);
    }
    const Kernel::Triangle_3 triangle = cgalTriangle(t);
    const bool degenerate = triangle.is_degenerate();
    const FilterTriangle filter({glm::dvec3(t.v0), glm::dvec3(t.v1), glm::dvec3(t.v2)});
    for (int z = lo.z; z <= hi.z; ++z)
        for (int y = lo.y; y <= hi.y; ++y)
            for (int x = lo.x; x <= hi.x; ++x) {
                const CGAL::Bbox_3 box = widenedBox(grid.voxelBounds(x, y, z), voxelMargin);
                Overlap overlap = degenerate ? Overlap::Unsure
                                             : filteredTriangleBoxOverlap(filter, {box.xmin(), box.ymin(), box.zmin()},
                                                                          {box.xmax(), box.ymax(), box.zmax()});
                ++counts.voxels;
                if (overlap == Overlap::Unsure) {
                    ++counts.exact;
                    overlap = exactOverlap(triangle, degenerate, box) ? Overlap::Yes : Overlap::No;
                }
                if (overlap == Overlap::Yes)
                    pairs.emplace_back(std::uint32_t(x + p.resolution.x * (y + std::uint64_t(p.resolution.y) * z)), i);
            }
}

// Pass 1, on the machine's cores (TBB): the (cell, triangle) pairs of fixed chunks of triangles,
// each chunk's in triangle order, so the result does not depend on the scheduling.
std::vector<CellPairs> binTriangles(UniformGrid& grid, float voxelMargin) {
    constexpr std::size_t kChunk = 64;  // small: a few large triangles (a floor, a wall) are much of the work
    const std::size_t count = grid.triangles.size();
    std::vector<CellPairs> chunks((count + kChunk - 1) / kChunk);
    std::vector<TestCounts> counts(chunks.size());
    tbb::parallel_for(std::size_t(0), chunks.size(), [&](std::size_t c) {
        CellPairs& pairs = chunks[c];
        pairs.reserve(kChunk * 8);
        for (std::size_t i = c * kChunk; i < std::min(count, (c + 1) * kChunk); ++i) {
            binTriangle(grid, std::uint32_t(i), voxelMargin, pairs, counts[c]);
            if (pairs.size() > std::numeric_limits<std::uint32_t>::max()) break;  // refused below
        }
    });
    std::uint64_t references = 0;
    for (std::size_t c = 0; c < chunks.size(); ++c) {
        references += chunks[c].size();
        grid.stats.voxelTests += counts[c].voxels;
        grid.stats.exactTests += counts[c].exact;
    }
    if (references > std::numeric_limits<std::uint32_t>::max())  // the cell offsets are uint32
        throw Error("grid: resolution " +
                    resolutionText({double(grid.params.resolution.x), double(grid.params.resolution.y), double(grid.params.resolution.z)}) +
                    " gives more than 4294967295 triangle references, more than its 32-bit offsets hold");
    return chunks;
}

// Pass 2: a counting sort of the pairs by cell (stable: ids ascend within a voxel), and the stats.
void sortByCell(UniformGrid& grid, const std::vector<CellPairs>& chunks) {
    const std::uint64_t cells = std::uint64_t(grid.params.resolution.x) * grid.params.resolution.y * grid.params.resolution.z;
    grid.cellOffsets.assign(cells + 1, 0);
    for (const CellPairs& pairs : chunks)
        for (const auto& [cell, tri] : pairs) ++grid.cellOffsets[cell + 1];
    std::uint32_t maxInCell = 0;
    std::uint64_t emptyCells = 0;
    for (std::uint64_t c = 0; c < cells; ++c) {
        maxInCell = std::max(maxInCell, grid.cellOffsets[c + 1]);
        emptyCells += grid.cellOffsets[c + 1] == 0;
        grid.cellOffsets[c + 1] += grid.cellOffsets[c];
    }
    grid.triangleList.resize(grid.cellOffsets.back());
    std::vector<std::uint32_t> cursor(grid.cellOffsets.begin(), grid.cellOffsets.end() - 1);
    for (const CellPairs& pairs : chunks)
        for (const auto& [cell, tri] : pairs) grid.triangleList[cursor[cell]++] = tri;
    GridStats& s = grid.stats;
    s.resolution = {grid.params.resolution.x, grid.params.resolution.y, grid.params.resolution.z};
    s.cells = cells;
    s.emptyFraction = static_cast<double>(emptyCells) / static_cast<double>(cells);
    s.references = grid.triangleList.size();
    s.referencesPerTriangle = static_cast<double>(s.references) / static_cast<double>(grid.triangles.size());
    s.maxReferencesInCell = maxInCell;
    s.bytes = grid.cellOffsets.size() * 4 + grid.triangleList.size() * 4 + grid.triangles.size() * triangleVertexBytes(grid.lattice);
}

}  // namespace

bool triangleOverlapsBox(const gpu::Triangle& t, const VoxelBox& box, float margin) {
    const Kernel::Triangle_3 triangle = cgalTriangle(t);
    return exactOverlap(triangle, triangle.is_degenerate(), widenedBox(box, margin));
}

float conservativeVoxelMargin(const Bounds3& gridBox, const std::vector<gpu::Ray>& rays,
                              const std::array<unsigned, 3>& resolution) {
    double largest = 0.0;
    for (int a = 0; a < 3; ++a) largest = std::max(largest, double(gridBox.max[a]) - gridBox.min[a]);
    for (const gpu::Ray& r : rays)
        for (int a = 0; a < 3; ++a) largest = std::max(largest, std::abs(double(r.originTMin[a]) - gridBox.min[a]));
    const float steps = float(resolution[0]) + float(resolution[1]) + float(resolution[2]);
    return float((4.0 * steps + 16.0) * largest * 0x1p-23);
}

UniformGrid buildUniformGrid(const TriangleMesh& mesh, const GridResolutionRule& rule,
                             std::uint64_t maxCells, float voxelMargin) {
    const auto start = std::chrono::steady_clock::now();
    validateSceneRange(mesh);
    UniformGrid grid;
    grid.params = gridFrame(mesh, rule, maxCells, voxelMargin);
    grid.lattice = mesh.lattice;
    grid.triangles.resize(mesh.triangles.size());
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
        const glm::uvec3& t = mesh.triangles[i];
        grid.triangles[i] = {glm::vec4(mesh.vertices[t[0]], 0.0f), glm::vec4(mesh.vertices[t[1]], 0.0f),
                             glm::vec4(mesh.vertices[t[2]], 0.0f)};
    }
    sortByCell(grid, binTriangles(grid, voxelMargin));
    grid.stats.voxelMargin = voxelMargin;
    grid.stats.buildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return grid;
}

}  // namespace rtbench
