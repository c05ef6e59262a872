// Rays for the method tests: random origins around a box and random directions, a seventh of
// them along an axis and another seventh parallel to an axis plane (fixed seed).
#pragma once
#include <cstring>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "kernels/gpu_layout.h"
#include "scene/mesh.h"

namespace rtbench {

inline std::vector<gpu::Ray> randomRays(const Bounds3& box, unsigned count, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f), s(-1.0f, 1.0f);
    std::vector<gpu::Ray> rays;
    const glm::vec3 lo = box.min - 0.3f * box.extent(), size = 1.6f * box.extent();
    for (unsigned i = 0; i < count; ++i) {
        const glm::vec3 o = lo + glm::vec3(u(rng), u(rng), u(rng)) * size;
        glm::vec3 d(s(rng), s(rng), s(rng));
        if (i % 7 == 3) d = glm::vec3(0.0f), d[i % 3] = s(rng) < 0 ? -1.0f : 1.0f;
        if (i % 7 == 5) d[i % 3] = 0.0f;
        if (glm::length(d) == 0.0f) d = glm::vec3(0, 1, 0);
        rays.push_back({glm::vec4(o, 0.0f), glm::vec4(d, gpu::kNoHitT)});
    }
    return rays;
}

// Fails the test, naming the first five, when hit records differ in any bit.
inline void expectIdentical(const std::vector<gpu::HitRecord>& gpuHits, const std::vector<gpu::HitRecord>& cpuHits) {
    ASSERT_EQ(gpuHits.size(), cpuHits.size());
    std::size_t differing = 0;
    for (std::size_t i = 0; i < gpuHits.size(); ++i) {
        if (std::memcmp(&gpuHits[i], &cpuHits[i], sizeof(gpu::HitRecord)) == 0) continue;
        if (++differing <= 5)
            ADD_FAILURE() << "ray " << i << ": GPU t=" << gpuHits[i].t << " prim=" << gpuHits[i].primitive
                          << " cells=" << gpuHits[i].cellsVisited << " tests=" << gpuHits[i].trianglesTested
                          << " | CPU t=" << cpuHits[i].t << " prim=" << cpuHits[i].primitive
                          << " cells=" << cpuHits[i].cellsVisited << " tests=" << cpuHits[i].trianglesTested;
    }
    EXPECT_EQ(differing, 0u);
}

// Two methods found the same nearest hit: the same primitive at the same distance, or, at an exact
// tie (a shared edge or vertex, coplanar triangles), different primitives at the same distance.
// Returns the rays where they differ otherwise.
inline std::size_t differentNearestHits(const std::vector<gpu::HitRecord>& a, const std::vector<gpu::HitRecord>& b) {
    std::size_t differing = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
        differing += a[i].primitive != b[i].primitive && !(a[i].primitive != gpu::kNoHit &&
                                                           b[i].primitive != gpu::kNoHit && a[i].t == b[i].t);
    return differing;
}

}  // namespace rtbench
