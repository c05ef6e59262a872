// The multipass tests' scenes (test_multipass_kernels.cpp, test_multipass_device_control.cpp): the
// hand scene, a 4x1x1 grid with hand-counted voxel lists and three rays whose passes the tests
// count by hand; and scene B with the rays and structures the tests trace it with.
#pragma once
#include <memory>
#include <vector>

#include "structures/bvh/bvh_build.h"
#include "structures/bvh/bvh_structure.h"
#include "structures/uniform_grid/grid_structure.h"
#include "scene/camera.h"
#include "scene/procedural.h"

#include "kernels/gpu_layout.h"
#include "structures/uniform_grid/uniform_grid.h"
#include "strategies/multipass/multipass_schedule.h"
#include "scene/mesh.h"
#include "tests/methods/hand_scenes.h"

namespace rtbench::hand {

// Grid 4x1x1 over [0,4]x[0,1]x[0,1]. Triangles (ids): 0 corner at x=0 (y,z in [0.8,1]),
// 1 corner at x=4, 2-3 a quad at x=2.5 split along y+z=1, 4-5 the same at x=3.5.
// Voxel lists: v0 {0}, v1 {}, v2 {2,3}, v3 {1,4,5}.
inline TriangleMesh handScene() {
    std::vector<Tri> tris = {{glm::vec3(0, 0.8f, 0.8f), glm::vec3(0, 1, 0.8f), glm::vec3(0, 0.8f, 1)},
                             {glm::vec3(4, 0.8f, 0.8f), glm::vec3(4, 1, 0.8f), glm::vec3(4, 0.8f, 1)}};
    for (float x : {2.5f, 3.5f}) {
        tris.push_back({glm::vec3(x, 0, 0), glm::vec3(x, 1, 0), glm::vec3(x, 0, 1)});  // y + z <= 1
        tris.push_back({glm::vec3(x, 1, 0), glm::vec3(x, 1, 1), glm::vec3(x, 0, 1)});  // y + z >= 1
    }
    return meshOf(tris);
}

inline UniformGrid handGrid() { return gridOf(handScene(), {4, 1, 1}); }

// Ray 0 from x=-1 along +x hits triangle 2 at t=3.5; ray 1 misses the box; ray 2 from x=5
// along -x hits triangle 4 at t=1.5.
inline std::vector<gpu::Ray> handRays() {
    return {ray({-1, 0.25f, 0.25f}, {1, 0, 0}), ray({-1, 5, 0.5f}, {1, 0, 0}), ray({5, 0.25f, 0.25f}, {-1, 0, 0})};
}

// Scene B (Christen 2005 Table 6.1): 48 x 40 rays of its own camera.
inline std::vector<gpu::Ray> sceneBRays() { return generatePrimaryRays(*proceduralCamera("christen_b", 70.0f), 48, 40); }

// Its grid at min_dim 8.
inline UniformGrid sceneBGrid() {
    GridResolutionRule rule;
    rule.minDim = 8;
    return buildUniformGrid(christenSceneB(), rule);
}

// That grid, then its BVH (leaves of up to 4).
inline std::vector<std::unique_ptr<Structure>> sceneBStructures() {
    std::vector<std::unique_ptr<Structure>> structures;
    structures.push_back(gridStructure(sceneBGrid()));
    structures.push_back(bvhStructure(buildBvh(christenSceneB(), BvhBuildOptions{})));
    return structures;
}

// The oracle's options: threshold, K, M, suppression, and where the oracle runs.
inline MultipassOptions multipassOptions(double threshold, unsigned k = 1, unsigned m = 1, bool suppress = false,
                                         bool deviceControl = false) {
    MultipassOptions o;
    o.oracleThreshold = threshold;
    o.traverseStepsPerPass = k;
    o.intersectionsPerPass = m;
    o.suppressFinishedReads = suppress;
    o.deviceControl = deviceControl;
    return o;
}

}  // namespace rtbench::hand
