// Hand-made scenes and rays whose answers are derived by hand (issue 15 §6): the kernels, the
// multipass walk and the CPU reference share their GLSL, so a bug there passes every GPU-against-
// CPU comparison; these tests assert numbers computed in their comments instead. The helpers run
// one structure every way it can run: CPU reference, branching kernel and multipass kernels on the
// test device (lavapipe), and the multipass simulator; every way must give the hand's answer.
#pragma once
#include <gtest/gtest.h>

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "strategies/branching/branching_strategy.h"
#include "structures/brute_force/brute_structure.h"
#include "structures/bvh/bvh_build.h"
#include "structures/bvh/bvh_structure.h"
#include "structures/uniform_grid/grid_structure.h"
#include "structures/uniform_grid/uniform_grid.h"
#include "strategies/multipass/multipass_simulator.h"
#include "strategies/multipass/multipass_strategy.h"
#include "structures/structure.h"
#include "scene/camera.h"
#include "scene/mesh.h"
#include "scene/procedural.h"

namespace rtbench::hand {

using Tri = std::array<glm::vec3, 3>;

// A mesh of separate triangles, ids in the order given.
inline TriangleMesh meshOf(const std::vector<Tri>& tris) {
    TriangleMesh m;
    m.name = "hand";
    for (const Tri& t : tris) {
        const unsigned base = unsigned(m.vertices.size());
        m.vertices.insert(m.vertices.end(), t.begin(), t.end());
        m.triangles.emplace_back(base, base + 1, base + 2);
    }
    return m;
}

// Two parallel mirrors, a floor y = 0 (triangles 0, 1) and a ceiling y = 4 (2, 3), both over
// x, z in [-8, 8] (tests/rays/test_reflection_rays.cpp derives their iterations by hand).
inline TriangleMesh parallelMirrors() {
    return meshOf({{glm::vec3(-8, 0, -8), glm::vec3(8, 0, -8), glm::vec3(-8, 0, 8)},
                   {glm::vec3(8, 0, -8), glm::vec3(8, 0, 8), glm::vec3(-8, 0, 8)},
                   {glm::vec3(-8, 4, -8), glm::vec3(8, 4, -8), glm::vec3(-8, 4, 8)},
                   {glm::vec3(8, 4, -8), glm::vec3(8, 4, 8), glm::vec3(-8, 4, 8)}});
}

inline gpu::Ray ray(glm::vec3 o, glm::vec3 d, float tMin = 0.0f, float tMax = gpu::kNoHitT) {
    return {glm::vec4(o, tMin), glm::vec4(d, tMax)};
}

// A hit record on triangle `primitive` at barycentrics (u, v) (t 0): what a shading pass reads.
inline gpu::HitRecord hitOn(std::uint32_t primitive, float u, float v) {
    gpu::HitRecord h{};
    h.primitive = primitive;
    h.u = u;
    h.v = v;
    return h;
}

inline const char* testName(std::uint32_t test) {
    return test == gpu::kTriangleTestWatertight ? "watertight" : "moller_trumbore";
}

// ---- structures, built the way the runner builds them ----

inline std::unique_ptr<Structure> bruteOf(const TriangleMesh& mesh, const DeviceInfo& device) {
    RunConfig run;
    run.values["structure.max_tests"] = 1e9;
    return bruteStructureType().build(mesh, {}, run, device);
}

inline UniformGrid gridOf(const TriangleMesh& mesh, std::array<unsigned, 3> resolution) {
    GridResolutionRule rule;
    rule.kind = GridResolutionRule::Kind::Explicit;
    rule.resolution = resolution;
    return buildUniformGrid(mesh, rule);
}

inline FlatBvh bvhOf(const TriangleMesh& mesh, unsigned leafSize) {
    BvhBuildOptions o;
    o.maxLeafSize = leafSize;
    o.embreeConfig = "threads=1";
    return buildBvh(mesh, o);
}

// A structure to build over a scene, by name: "brute_force", "uniform_grid RxSxT", "bvh leaf N".
struct StructureCase {
    std::string name;
    std::function<std::unique_ptr<Structure>(const TriangleMesh&, const DeviceInfo&)> build;
};

inline StructureCase bruteCase() { return {"brute_force", bruteOf}; }
inline StructureCase gridCase(std::array<unsigned, 3> r) {
    return {"uniform_grid " + std::to_string(r[0]) + "x" + std::to_string(r[1]) + "x" + std::to_string(r[2]),
            [r](const TriangleMesh& m, const DeviceInfo&) { return gridStructure(gridOf(m, r)); }};
}
inline StructureCase bvhCase(unsigned leaf) {
    return {"bvh leaf " + std::to_string(leaf),
            [leaf](const TriangleMesh& m, const DeviceInfo&) { return bvhStructure(bvhOf(m, leaf)); }};
}

// ---- every way a structure runs ----

struct Answers {
    std::vector<gpu::HitRecord> cpu, branching, multipass, simulated;
};

// Branching and multipass (K = M = 1, oracle 0.2) on the device, the CPU reference and the
// multipass simulator, on the same rays. Multipass records carry the same counters as branching.
inline Answers answersOf(VulkanContext& vk, const Structure& s, const std::vector<gpu::Ray>& rays) {
    Answers a;
    a.cpu = s.trace(rays);
    a.branching = runBranching(vk, s, rays, {64, 0, 1}).hits;
    const MultipassOptions o;
    a.multipass = runMultipass(vk, s, rays, o, {64, 0, 1}).hits;
    a.simulated = simulateMultipass(s, rays, o).hits;
    return a;
}

// The hand's answer for one ray: the triangle (kNoHit: a miss) and its distance; counters when
// given (-1: not asserted).
struct Expect {
    std::uint32_t primitive;
    float t = 0.0f;
    int cells = -1, tests = -1, steps = -1;
};

inline void expectRecord(const gpu::HitRecord& h, const Expect& e, const std::string& where) {
    SCOPED_TRACE(where);
    EXPECT_EQ(h.primitive, e.primitive);
    if (e.primitive != gpu::kNoHit) {
        EXPECT_EQ(h.t, e.t);
    }
    if (e.cells >= 0) {
        EXPECT_EQ(h.cellsVisited, std::uint32_t(e.cells));
    }
    if (e.tests >= 0) {
        EXPECT_EQ(h.trianglesTested, std::uint32_t(e.tests));
    }
    if (e.steps >= 0) {
        EXPECT_EQ(h.traversalSteps, std::uint32_t(e.steps));
    }
}

// Every way's record of ray i equals the hand's.
inline void expectAnswers(const Answers& a, std::size_t i, const Expect& e) {
    const std::string ray = "ray " + std::to_string(i);
    expectRecord(a.cpu.at(i), e, ray + ": CPU reference");
    expectRecord(a.branching.at(i), e, ray + ": branching kernel");
    expectRecord(a.multipass.at(i), e, ray + ": multipass kernels");
    expectRecord(a.simulated.at(i), e, ray + ": multipass simulator");
}

// ---- scenes ----

// A valley: two triangles sharing the edge x = z = 0, 0 <= y <= 4.
//   triangle 0 ("R") rises to the right, in the plane z = x:  (0,0,0) (0,4,0) (2,2,2)
//   triangle 1 ("L") rises to the left,  in the plane z = -x: (0,0,0) (0,4,0) (-2,2,2)
// Ray 0 comes down from the left, o = (-1.5, 2, 3), d = (1, 0, -2): on it x = -1.5 + t and
// z = 3 - 2t; it meets z = -x only at t = 1.5 and z = x only at t = 1.5, the point (0, 2, 0) of the
// shared edge. Ray 1 is its mirror image, o = (1.5, 2, 3), d = (-1, 0, -2).
// Every value either test computes here is exact (hand-computed, for ray 0):
//   Moller-Trumbore, L: e1 = (0,4,0), e2 = (-2,2,2), p = d x e2 = (4,2,2), det = 8, s = (-1.5,2,3),
//     u = s.p / 8 = 4/8 = 0.5, q = s x e1 = (-12,0,-6), v = d.q / 8 = 0, t = e2.q / 8 = 12/8 = 1.5;
//   R: p = (4,-6,2), det = -24, s.p = -12, u = -12 * fl(-1/24) = 0.5 and t = -36 * fl(-1/24) = 1.5
//     after rounding (fl(1/24) = 1/24 (1 + 2^-25), within half an ulp of each product).
//   watertight: kz = z (|d.z| = 2 largest), d.z < 0 swaps kx, ky: kx = y, ky = x; shear
//     (-0, -0.5, -0.5); relative to o the shared vertices shear to (-2, 0) and (2, 0), L's third
//     vertex to (0, -1), R's to (0, 3): L's edge functions (2, 2, 0), det 4, scaled t 6: t = 1.5;
//     R's (-6, -6, 0), det -12, scaled t -18: t = 1.5. The zero is exact (the ray meets the edge).
inline TriangleMesh valley() {
    return meshOf({{glm::vec3(0, 0, 0), glm::vec3(0, 4, 0), glm::vec3(2, 2, 2)},
                   {glm::vec3(0, 0, 0), glm::vec3(0, 4, 0), glm::vec3(-2, 2, 2)}});
}
inline std::vector<gpu::Ray> valleyRays() { return {ray({-1.5f, 2, 3}, {1, 0, -2}), ray({1.5f, 2, 3}, {-1, 0, -2})}; }

// ---- the multipass tests' scenes (tests/strategies/multipass/): a 4x1x1 grid with hand-counted
// voxel lists and three rays whose passes they count by hand; and scene B with the rays and
// structures they trace it with ----

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

}  // namespace rtbench::hand
