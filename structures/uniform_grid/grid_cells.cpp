#include "grid_cells.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>
#include <sys/mman.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>

#include "core/error.h"
#include "structures/triangle_store.h"
#include "triangle_box_filter.h"
#include "voxel_block_filter.h"
#include "voxel_row.h"

namespace rtbench {

namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

// Candidate cell range of [vmin, vmax] on one axis. The float cell computation may be off by one
// within rounding of a boundary, so a coordinate that close to one widens the range by a cell;
// the exact predicate then decides. Clamped so that a NaN goes to the grid's edge too (each
// comparison with it is false): the range is always within [0, resolution - 1].
void candidateRange(float vmin, float vmax, float boxMin, float invCellSize, unsigned resolution, int& lo, int& hi) {
    constexpr double kNear = 1e-4;  // in cells; rounding errors are ~1e-6 cells
    const double localMin = (double(vmin) - boxMin) * invCellSize;
    const double localMax = (double(vmax) - boxMin) * invCellSize;
    double cellMin = std::floor(localMin), cellMax = std::floor(localMax);
    if (localMin - cellMin < kNear) cellMin -= 1.0;
    if (cellMax + 1.0 - localMax < kNear) cellMax += 1.0;
    const double last = static_cast<double>(resolution) - 1.0;
    const double loClamped = cellMin > 0.0 ? cellMin : 0.0, hiClamped = cellMax < last ? cellMax : last;
    lo = static_cast<int>(loClamped < last ? loClamped : last);
    hi = static_cast<int>(hiClamped > 0.0 ? hiClamped : 0.0);
}

// The CGAL triangle of a grid triangle.
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

// A voxel's box widened by the margin, as every test sees it.
CGAL::Bbox_3 widenedBox(const VoxelBox& box, float margin) {
    const double m = margin;
    return CGAL::Bbox_3(box.min.x - m, box.min.y - m, box.min.z - m, box.max.x + m, box.max.y + m, box.max.z + m);
}

using CellPairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;  // (cell, triangle)

// Voxels tested, and those CGAL decided.
struct TestCounts {
    std::uint64_t voxels = 0, exact = 0;
    void add(const TestCounts& other) { voxels += other.voxels, exact += other.exact; }
};

// Every voxel's widened box, per axis: voxel (x, y, z) spans [lo[0][x], hi[0][x]] x ...
struct VoxelFaces {
    std::array<std::vector<double>, 3> lo, hi;
    VoxelFaces(const UniformGrid& grid, float voxelMargin) {
        const glm::uvec3 r(grid.params.resolution);
        for (unsigned c = 0; c < std::max({r.x, r.y, r.z}); ++c) {
            const CGAL::Bbox_3 box = widenedBox(grid.voxelBounds(std::min(c, r.x - 1), std::min(c, r.y - 1), std::min(c, r.z - 1)), voxelMargin);
            for (int a = 0; a < 3; ++a)
                if (c < r[a]) lo[a].push_back(box.min(a)), hi[a].push_back(box.max(a));
        }
    }
};

// One triangle as pass 1 tests it: its candidate voxels and the tests that decide them.
struct BinnedTriangle {
    std::uint32_t id;
    const gpu::Triangle& triangle;
    const VoxelBlockFilter& block;
    glm::ivec3 lo, hi;  // candidate voxels, inclusive
    glm::dvec3 boundsLo, boundsHi;  // the triangle's bounding box
    bool degenerate = false;
    // Within its one candidate's slab on two axes: a voxel of the row meets it iff the voxel's
    // slab on the third meets its extent there (the triangle's projection on that axis), exact.
    bool boxDecides = false;

    BinnedTriangle(const UniformGrid& grid, const VoxelFaces& faces, std::uint32_t i, float voxelMargin, VoxelBlockFilter& filter)
        : id(i), triangle(grid.triangles[i]), block(filter) {
        const gpu::GridParams& p = grid.params;
        VoxelBlock candidates;
        int containedAxes = 0;
        for (int a = 0; a < 3; ++a) {
            const float vmin = std::min({triangle.v0[a], triangle.v1[a], triangle.v2[a]});
            const float vmax = std::max({triangle.v0[a], triangle.v1[a], triangle.v2[a]});
            candidateRange(vmin - voxelMargin, vmax + voxelMargin, p.boundsMin[a], p.invCellSize[a], p.resolution[a], lo[a], hi[a]);
            candidates.lo[a] = faces.lo[a].data() + lo[a];
            candidates.hi[a] = faces.hi[a].data() + lo[a];
            boundsLo[a] = vmin, boundsHi[a] = vmax;
            containedAxes += lo[a] == hi[a] && faces.lo[a][lo[a]] <= boundsLo[a] && boundsHi[a] <= faces.hi[a][lo[a]];
        }
        boxDecides = containedAxes >= 2;
        if (boxDecides) return;
        candidates.size = hi - lo + 1;
        filter.reset(vertices(), candidates);
        degenerate = !filter.proper() && cgalTriangle(triangle).is_degenerate();  // CGAL decides what the filter cannot
    }
    bool boxesMeet(const VoxelFaces& faces, const glm::ivec3& voxel) const {
        for (int a = 0; a < 3; ++a)
            if (boundsHi[a] < faces.lo[a][voxel[a]] || boundsLo[a] > faces.hi[a][voxel[a]]) return false;
        return true;
    }
    std::array<glm::dvec3, 3> vertices() const { return {glm::dvec3(triangle.v0), glm::dvec3(triangle.v1), glm::dvec3(triangle.v2)}; }

    // Voxel (x, y, z): the boxes where they decide; else the block filter; where it is unsure, the
    // per-sign filter; where both are, CGAL's exact test. The answer is always the exact test's.
    bool meets(const VoxelFaces& faces, int x, int y, int z, TestCounts& counts) const {
        ++counts.voxels;
        if (boxDecides) return boxesMeet(faces, glm::ivec3(x, y, z));
        Overlap overlap = degenerate ? Overlap::Unsure : block.at(x - lo.x, y - lo.y, z - lo.z);
        if (overlap != Overlap::Unsure) return overlap == Overlap::Yes;
        const glm::dvec3 boxLo(faces.lo[0][x], faces.lo[1][y], faces.lo[2][z]), boxHi(faces.hi[0][x], faces.hi[1][y], faces.hi[2][z]);
        if (!degenerate) overlap = filteredTriangleBoxOverlap(FilterTriangle(vertices()), boxLo, boxHi);
        if (overlap != Overlap::Unsure) return overlap == Overlap::Yes;
        ++counts.exact;
        return exactOverlap(cgalTriangle(triangle), degenerate, CGAL::Bbox_3(boxLo.x, boxLo.y, boxLo.z, boxHi.x, boxHi.y, boxHi.z));
    }
};

// The block's axes as the row walk takes them: rows along its longest axis, consecutive rows
// along the next, layers along the shortest.
struct RowAxes {
    int row = 0, next = 1, layer = 2;
    explicit RowAxes(const glm::ivec3& size) {
        std::array<int, 3> axes{0, 1, 2};
        std::stable_sort(axes.begin(), axes.end(), [&](int a, int b) { return size[a] > size[b]; });
        row = axes[0], next = axes[1], layer = axes[2];
    }
};

// Voxel v's cell in the grid's x-fastest order (Purcell et al. 2002 Fig. 4).
std::uint32_t cellIndex(const UniformGrid& grid, const glm::ivec3& v) {
    const glm::uvec3 r(grid.params.resolution);
    return std::uint32_t(v.x + r.x * (v.y + std::uint64_t(r.y) * v.z));
}

// Rows [nextLo, nextHi] of one layer of a triangle's block.
struct RowRun {
    int layer, nextLo, nextHi;
};

// Appends the (cell, id) pair of every voxel of the run the triangle meets, each row's span found
// from the row before's (voxel_row.h).
void binRows(const UniformGrid& grid, const VoxelFaces& faces, const BinnedTriangle& t, const RowAxes& axes, const RowRun& run,
             CellPairs& pairs, TestCounts& counts) {
    glm::ivec3 voxel;
    voxel[axes.layer] = run.layer;
    VoxelSpan span;
    for (voxel[axes.next] = run.nextLo; voxel[axes.next] <= run.nextHi; ++voxel[axes.next]) {
        const auto meets = [&](int i) {
            glm::ivec3 v = voxel;
            v[axes.row] = i;
            return t.meets(faces, v.x, v.y, v.z, counts);
        };
        span = findSpan(t.lo[axes.row], t.hi[axes.row], span, meets);
        for (voxel[axes.row] = span.first; voxel[axes.row] <= span.last; ++voxel[axes.row])
            pairs.emplace_back(cellIndex(grid, voxel), t.id);
    }
}

// Appends the pairs of a small block's voxels, testing each.
void binVoxels(const UniformGrid& grid, const VoxelFaces& faces, const BinnedTriangle& t, CellPairs& pairs, TestCounts& counts) {
    for (int z = t.lo.z; z <= t.hi.z; ++z)
        for (int y = t.lo.y; y <= t.hi.y; ++y)
            for (int x = t.lo.x; x <= t.hi.x; ++x)
                if (t.meets(faces, x, y, z, counts)) pairs.emplace_back(cellIndex(grid, glm::ivec3(x, y, z)), t.id);
}

// Appends triangle i's pairs: a small block voxel by voxel, a larger one row by row in runs of
// rows. A triangle with many candidates (a floor, a wall) has its runs binned on all cores and
// appended in order, so the pairs are the same whatever the scheduling.
void binTriangle(const UniformGrid& grid, const VoxelFaces& faces, std::uint32_t i, float voxelMargin, VoxelBlockFilter& filter,
                 CellPairs& pairs, TestCounts& counts) {
    constexpr std::uint64_t kParallelVoxels = 1u << 14;
    constexpr int kRowsPerRun = 16;
    constexpr std::uint64_t kSmallBlock = 64;  // voxel by voxel: cheaper than a walk over such short rows
    const BinnedTriangle t(grid, faces, i, voxelMargin, filter);
    const glm::ivec3 size = t.hi - t.lo + 1;
    const std::uint64_t voxels = std::uint64_t(size.x) * std::uint64_t(size.y) * std::uint64_t(size.z);
    if (voxels <= kSmallBlock) return binVoxels(grid, faces, t, pairs, counts);
    const RowAxes axes(size);
    std::vector<RowRun> runs;
    for (int layer = t.lo[axes.layer]; layer <= t.hi[axes.layer]; ++layer)
        for (int next = t.lo[axes.next]; next <= t.hi[axes.next]; next += kRowsPerRun)
            runs.push_back({layer, next, std::min(next + kRowsPerRun - 1, t.hi[axes.next])});
    if (runs.size() == 1 || voxels < kParallelVoxels) {
        for (const RowRun& run : runs) binRows(grid, faces, t, axes, run, pairs, counts);
        return;
    }
    std::vector<CellPairs> runPairs(runs.size());
    std::vector<TestCounts> runCounts(runs.size());
    tbb::parallel_for(std::size_t(0), runs.size(), [&](std::size_t k) { binRows(grid, faces, t, axes, runs[k], runPairs[k], runCounts[k]); });
    for (std::size_t k = 0; k < runs.size(); ++k) {
        pairs.insert(pairs.end(), runPairs[k].begin(), runPairs[k].end());
        counts.add(runCounts[k]);
    }
}

std::string resolutionText(const glm::uvec4& r) {
    return std::to_string(r.x) + "x" + std::to_string(r.y) + "x" + std::to_string(r.z);
}

// Pass 1, on the machine's cores (TBB): the (cell, triangle) pairs of fixed chunks of triangles,
// each chunk's in triangle order, so the result does not depend on the scheduling.
std::vector<CellPairs> binTriangles(UniformGrid& grid, float voxelMargin) {
    constexpr std::size_t kChunk = 64;
    const std::size_t count = grid.triangles.size();
    const VoxelFaces faces(grid, voxelMargin);
    std::vector<CellPairs> chunks((count + kChunk - 1) / kChunk);
    std::vector<TestCounts> counts(chunks.size());
    tbb::parallel_for(std::size_t(0), chunks.size(), [&](std::size_t c) {
        CellPairs& pairs = chunks[c];
        pairs.reserve(kChunk * 8);
        VoxelBlockFilter filter;  // its tables reused by the chunk's triangles
        for (std::size_t i = c * kChunk; i < std::min(count, (c + 1) * kChunk); ++i) {
            binTriangle(grid, faces, std::uint32_t(i), voxelMargin, filter, pairs, counts[c]);
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
        throw Error("grid: resolution " + resolutionText(grid.params.resolution) +
                    " gives more than 4294967295 triangle references, more than its 32-bit offsets hold");
    return chunks;
}

// Zeroed storage for `count` offsets. Asks Linux for 2 MB pages: a 2.9M-cell table otherwise
// takes some 2,800 page faults, which cost as much as the rest of the sort.
void zeroedOffsets(std::vector<std::uint32_t>& offsets, std::uint64_t count) {
    offsets.clear();
    offsets.reserve(count);
    constexpr std::uintptr_t kHugePage = std::uintptr_t(1) << 21;
    const auto begin = (reinterpret_cast<std::uintptr_t>(offsets.data()) + kHugePage - 1) & ~(kHugePage - 1);
    const auto end = reinterpret_cast<std::uintptr_t>(offsets.data() + count) & ~(kHugePage - 1);
    if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);  // a hint: ignored where unsupported
    offsets.assign(count, 0);
}

// Each cell's count becomes its end (the counts summed up to it), 8 cells at a time: an inclusive
// scan within the 8 lanes (three shifted adds), plus the sum before them. The clones (AVX2, the
// baseline) add the same integers, so they give the same ends. Returns the sum of all.
__attribute__((target_clones("avx2", "default"))) std::uint32_t countsToEnds(std::uint32_t* counts, std::uint64_t cells) {
    typedef std::uint32_t Lanes8 __attribute__((vector_size(32)));
    const Lanes8 zero{}, by1{8, 0, 1, 2, 3, 4, 5, 6}, by2{8, 8, 0, 1, 2, 3, 4, 5}, by4{8, 8, 8, 8, 0, 1, 2, 3};
    Lanes8 before{};
    std::uint64_t c = 0;
    for (; c + 8 <= cells; c += 8) {
        Lanes8 v;
        std::memcpy(&v, counts + c, sizeof v);
        v += __builtin_shuffle(v, zero, by1);
        v += __builtin_shuffle(v, zero, by2);
        v += __builtin_shuffle(v, zero, by4);
        v += before;
        std::memcpy(counts + c, &v, sizeof v);
        before = zero + v[7];
    }
    std::uint32_t sum = before[0];
    for (; c < cells; ++c) counts[c] = sum += counts[c];
    return sum;
}

// Pass 2: a counting sort of the pairs by cell (stable: ids ascend within a voxel), and the stats.
// Each cell's count, summed, gives its end; the pairs, placed from the last back, step every end
// down to its start.
void sortByCell(UniformGrid& grid, const std::vector<CellPairs>& chunks) {
    const std::uint64_t cells = std::uint64_t(grid.params.resolution.x) * grid.params.resolution.y * grid.params.resolution.z;
    std::vector<std::uint32_t>& offsets = grid.cellOffsets;
    zeroedOffsets(offsets, cells + 1);
    std::uint32_t maxInCell = 0;
    std::uint64_t filledCells = 0;
    for (const CellPairs& pairs : chunks)
        for (const auto& [cell, tri] : pairs) {
            filledCells += offsets[cell] == 0;
            maxInCell = std::max(maxInCell, ++offsets[cell]);
        }
    offsets[cells] = countsToEnds(offsets.data(), cells);
    grid.triangleList.resize(offsets[cells]);
    for (auto chunk = chunks.rbegin(); chunk != chunks.rend(); ++chunk)
        for (auto pair = chunk->rbegin(); pair != chunk->rend(); ++pair) grid.triangleList[--offsets[pair->first]] = pair->second;
    GridStats& s = grid.stats;
    s.resolution = {grid.params.resolution.x, grid.params.resolution.y, grid.params.resolution.z};
    s.cells = cells;
    s.emptyFraction = static_cast<double>(cells - filledCells) / static_cast<double>(cells);
    s.references = grid.triangleList.size();
    s.referencesPerTriangle = static_cast<double>(s.references) / static_cast<double>(grid.triangles.size());
    s.maxReferencesInCell = maxInCell;
    s.bytes = grid.cellOffsets.size() * 4 + grid.triangleList.size() * 4 + grid.triangles.size() * triangleVertexBytes(grid.lattice);
}

}  // namespace

void fillCellLists(UniformGrid& grid, float voxelMargin) { sortByCell(grid, binTriangles(grid, voxelMargin)); }

bool triangleOverlapsBox(const gpu::Triangle& t, const VoxelBox& box, float margin) {
    const Kernel::Triangle_3 triangle = cgalTriangle(t);
    return exactOverlap(triangle, triangle.is_degenerate(), widenedBox(box, margin));
}

}  // namespace rtbench
