#include "uniform_grid.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "core/error.h"
#include "grid_cells.h"
#include "scene/scene_limits.h"

namespace rtbench {

namespace {

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

}  // namespace

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
    fillCellLists(grid, voxelMargin);
    grid.stats.voxelMargin = voxelMargin;
    grid.stats.buildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return grid;
}

}  // namespace rtbench
