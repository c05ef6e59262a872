// The DDA (Amanatides & Woo) against a brute-force slab test over every voxel.
#include <gtest/gtest.h>

#include <random>

#include "structures/uniform_grid/grid_reference.h"
#include "scene/procedural.h"

namespace rtbench {
namespace {

// A grid over [-1, 3] x [0, 2] x [1, 4] with 8 x 5 x 6 cells (non-cubic voxels).
UniformGrid testGrid() {
    TriangleMesh mesh;
    appendBox(mesh, {-1, 0, 1}, {3, 2, 4});
    GridResolutionRule rule;
    rule.kind = GridResolutionRule::Kind::Explicit;
    rule.resolution = {8, 5, 6};
    return buildUniformGrid(mesh, rule);
}

struct Interval {
    double enter, leave;  // the ray's parameter range inside a closed voxel (enter > leave: none)
    bool interior;        // the ray passes through the open interior for a positive length
};

// Slab test in double precision for one voxel, clipped to the ray's [tMin, tMax].
Interval slab(const gpu::Ray& ray, const VoxelBox& b, double eps) {
    double enter = ray.originTMin.w, leave = ray.directionTMax.w;
    bool interior = true;
    for (int a = 0; a < 3; ++a) {
        const double o = ray.originTMin[a], d = ray.directionTMax[a];
        if (d == 0.0) {
            if (o < b.min[a] || o > b.max[a]) return {1, 0, false};
            interior = interior && o > b.min[a] && o < b.max[a];
            continue;
        }
        double t0 = (b.min[a] - o) / d, t1 = (b.max[a] - o) / d;
        if (t0 > t1) std::swap(t0, t1);
        enter = std::max(enter, t0);
        leave = std::min(leave, t1);
    }
    return {enter, leave, interior && leave - enter > eps};
}

// Every voxel whose interior the ray crosses is visited; every visited voxel is touched by the
// ray (closed box, within eps); visits are 6-connected steps in order of entry, never repeated.
void expectDdaMatchesSlabs(const UniformGrid& grid, const gpu::Ray& ray) {
    const std::vector<glm::ivec3> visited = ddaVoxels(grid, ray);
    const auto& r = grid.stats.resolution;
    const double eps = 1e-4 * std::min({grid.params.cellSize.x, grid.params.cellSize.y, grid.params.cellSize.z}) /
                       glm::length(glm::vec3(ray.directionTMax));
    std::set<std::tuple<int, int, int>> seen;
    double lastEnter = -1e30;
    for (std::size_t i = 0; i < visited.size(); ++i) {
        const glm::ivec3 c = visited[i];
        ASSERT_TRUE(c.x >= 0 && c.y >= 0 && c.z >= 0 && c.x < int(r[0]) && c.y < int(r[1]) && c.z < int(r[2]));
        ASSERT_TRUE(seen.insert({c.x, c.y, c.z}).second) << "voxel visited twice";
        const Interval in = slab(ray, grid.voxelBounds(c.x, c.y, c.z), eps);
        EXPECT_GE(in.leave - in.enter, -eps) << "visited voxel " << c.x << "," << c.y << "," << c.z
                                             << " that the ray does not touch";
        EXPECT_GE(in.enter, lastEnter - eps) << "voxels out of order";
        lastEnter = in.enter;
        if (i > 0) {
            const glm::ivec3 step = glm::abs(c - visited[i - 1]);
            EXPECT_EQ(step.x + step.y + step.z, 1) << "not a 6-connected step";
        }
    }
    for (unsigned z = 0; z < r[2]; ++z)
        for (unsigned y = 0; y < r[1]; ++y)
            for (unsigned x = 0; x < r[0]; ++x)
                if (slab(ray, grid.voxelBounds(x, y, z), eps).interior) {
                    EXPECT_TRUE(seen.count({int(x), int(y), int(z)}))
                        << "missed voxel " << x << "," << y << "," << z << " that the ray crosses";
                }
}

gpu::Ray makeRay(glm::vec3 o, glm::vec3 d, float tMax = gpu::kNoHitT) {
    return {glm::vec4(o, 0.0f), glm::vec4(d, tMax)};
}

TEST(Dda, VisitsExactlyTheVoxelsTheRayCrossesForRandomRays) {
    const UniformGrid grid = testGrid();
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), far(-6.0f, 8.0f);
    for (int i = 0; i < 2000; ++i) {
        const glm::vec3 o(far(rng), far(rng), far(rng));
        glm::vec3 d(u(rng), u(rng), u(rng));
        if (i % 4 == 1) d[i % 3] = 0.0f;                     // parallel to one axis plane
        if (i % 4 == 2) d = glm::vec3(0.0f), d[i % 3] = u(rng) < 0 ? -1.0f : 1.0f;  // along an axis
        if (glm::length(d) == 0.0f) d = glm::vec3(1, 0, 0);
        // Half aim at a random point in the box, so most rays hit it.
        if (i % 2 == 0) d = glm::vec3(-1 + 4 * (u(rng) + 1) / 2, (u(rng) + 1), 1 + 3 * (u(rng) + 1) / 2) - o;
        SCOPED_TRACE("ray " + std::to_string(i));
        expectDdaMatchesSlabs(grid, makeRay(o, d));
    }
}

TEST(Dda, RaysStartingInsideTheGridAndOnVoxelBoundaries) {
    const UniformGrid grid = testGrid();  // boundaries: x = -1 + 0.5 i, y = 0.4 j, z = 1 + 0.5 k
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::uniform_int_distribution<int> ix(0, 8), iy(0, 5), iz(0, 6);
    for (int i = 0; i < 2000; ++i) {
        glm::vec3 o(-1.0f + 0.5f * ix(rng), 0.4f * iy(rng), 1.0f + 0.5f * iz(rng));  // a lattice corner
        if (i % 3 == 1) o.x += 0.5f * (u(rng) + 1.0f) * 0.5f;  // on a face or an edge only
        if (i % 3 == 2) o = glm::vec3(1.0f + 2.0f * u(rng), 1.0f + u(rng), 2.5f + 1.5f * u(rng));  // inside
        glm::vec3 d(u(rng), u(rng), u(rng));
        if (i % 5 == 0) d = glm::vec3(0.0f), d[i % 3] = u(rng) < 0 ? -1.0f : 1.0f;  // along a face
        if (i % 5 == 1) d[(i + 1) % 3] = 0.0f;
        if (glm::length(d) == 0.0f) d = glm::vec3(0, 0, 1);
        SCOPED_TRACE("ray " + std::to_string(i));
        expectDdaMatchesSlabs(grid, makeRay(o, d));
    }
}

TEST(Dda, RayEndingInsideTheGridStopsThere) {
    const UniformGrid grid = testGrid();
    // Along +x through voxel row y = 0.5, z = 1.25, ending at x = 0.25 (voxel 2).
    const gpu::Ray ray = makeRay({-3.0f, 0.5f, 1.25f}, {1.0f, 0.0f, 0.0f}, 3.25f);
    const std::vector<glm::ivec3> v = ddaVoxels(grid, ray);
    ASSERT_EQ(v.size(), 3u);
    EXPECT_EQ(v[0], glm::ivec3(0, 1, 0));
    EXPECT_EQ(v[2], glm::ivec3(2, 1, 0));
    expectDdaMatchesSlabs(grid, ray);
}

TEST(Dda, RayMissingTheBoxVisitsNothing) {
    const UniformGrid grid = testGrid();
    EXPECT_TRUE(ddaVoxels(grid, makeRay({-5, 5, 0}, {1, 0, 0})).empty());
    EXPECT_TRUE(ddaVoxels(grid, makeRay({0, 1, 2}, {0, 0, 1}, 0.0f)).size() == 1);  // zero-length inside
    EXPECT_TRUE(ddaVoxels(grid, makeRay({5, 1, 2}, {1, 0, 0})).empty());           // pointing away
}

}  // namespace
}  // namespace rtbench
