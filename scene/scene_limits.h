// The coordinate range every method (GPU kernels, CPU reference, Embree) handles, and the checks
// that hold scenes and rays to it before any of them sees them. Outside it a method crashes
// (Embree asserts on ray origins beyond 1.844e18), overflows (the kernels' Moller-Trumbore
// products become inf, then NaN) or underflows (products become subnormal or zero): so a run is
// refused with the range named instead.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "../kernels/gpu_layout.h"
#include "core/error.h"
#include "mesh.h"

namespace rtbench {

// |vertex coordinate| <= 2^38 (about 2.7e11) and |ray origin| <= 2^40 (about 1.1e12), |ray
// direction component| <= 2^24. Then in Moller-Trumbore (kernels/ray_math.glsl) the
// edges are below 2^39, s = o - v0 below 1.25 * 2^40, q = s x e1 below 1.25 * 2^80, and the
// largest dot products, e2 . q and det = e1 . (d x e2), below 3.75 * 2^119 (about 2.5e36) and
// 3 * 2^103: under FLT_MAX (3.4e38) with a margin. Embree's bound on origins and vertices
// (1.844e18, FLT_LARGE) lies far beyond.
constexpr float kMaxVertexCoordinate = 0x1p38f;
constexpr float kMaxRayOrigin = 0x1p40f;
constexpr float kMaxDirectionComponent = 0x1p24f;

// The scene box's largest extent >= 2^-26 (about 1.5e-8). Moller-Trumbore's products scale as
// edge^2 x distance (e2 . q, with q = s x e1); for a triangle down to 2^-24 of the box (float's
// resolution of it: smaller ones are degenerate) seen from a camera at least the box's size away
// they stay of the order of (2^-24 x 2^-26)^2 x 2^-26 = 2^-126 = FLT_MIN or above: out of the
// subnormal range, where precision is lost and where a device that flushes subnormals to zero
// (Vulkan allows it unless DenormPreserve is requested) would part from the CPU reference.
constexpr float kMinSceneExtent = 0x1p-26f;

inline std::string formatFloat(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.4g", v);
    return text;
}

inline std::string sceneRangeText() {
    return "the methods handle vertex coordinates within +-" + formatFloat(kMaxVertexCoordinate) +
           " (2^38) and a scene box whose largest extent is at least " + formatFloat(kMinSceneExtent) + " (2^-26)";
}

// Throws rtbench::Error unless every vertex is finite and within kMaxVertexCoordinate, and the
// box's largest extent is at least kMinSceneExtent.
inline void validateSceneRange(const TriangleMesh& mesh) {
    if (mesh.triangles.empty()) throw Error("scene " + mesh.name + ": it has no triangles");
    Bounds3 box;
    for (const glm::uvec3& t : mesh.triangles)
        for (int k = 0; k < 3; ++k) {
            const glm::vec3& v = mesh.vertices[t[k]];
            for (int a = 0; a < 3; ++a)
                if (!(std::fabs(v[a]) <= kMaxVertexCoordinate))  // also false for NaN
                    throw Error("scene " + mesh.name + ": vertex (" + formatFloat(v.x) + ", " + formatFloat(v.y) +
                                ", " + formatFloat(v.z) + ") is out of range: " + sceneRangeText());
            box.extend(v);
        }
    const glm::vec3 e = box.extent();
    const float largest = std::max({e.x, e.y, e.z});
    if (largest < kMinSceneExtent)
        throw Error("scene " + mesh.name + ": its box is " + formatFloat(e.x) + " x " + formatFloat(e.y) + " x " +
                    formatFloat(e.z) + ", too small: " + sceneRangeText());
}

inline std::string rayRangeText() {
    return "the methods handle ray origins within +-" + formatFloat(kMaxRayOrigin) +
           " (2^40), direction components of 0 or between FLT_MIN and " + formatFloat(kMaxDirectionComponent) +
           " (2^24) in magnitude, and 0 <= tMin <= tMax";
}

// Throws rtbench::Error naming the first ray outside the range every method handles.
inline void validateRays(const std::vector<gpu::Ray>& rays) {
    for (std::size_t i = 0; i < rays.size(); ++i) {
        const glm::vec4& o = rays[i].originTMin;
        const glm::vec4& d = rays[i].directionTMax;
        bool ok = o.w >= 0.0f && d.w >= o.w && d.w <= gpu::kNoHitT && (d.x != 0.0f || d.y != 0.0f || d.z != 0.0f);
        for (int a = 0; a < 3; ++a) {
            const float m = std::fabs(d[a]);
            ok = ok && std::fabs(o[a]) <= kMaxRayOrigin &&
                 (m == 0.0f || (m >= std::numeric_limits<float>::min() && m <= kMaxDirectionComponent));
        }
        if (!ok)
            throw Error("ray " + std::to_string(i) + " (origin " + formatFloat(o.x) + ", " + formatFloat(o.y) + ", " +
                        formatFloat(o.z) + ", direction " + formatFloat(d.x) + ", " + formatFloat(d.y) + ", " +
                        formatFloat(d.z) + ", t in [" + formatFloat(o.w) + ", " + formatFloat(d.w) +
                        "]) is out of range: " + rayRangeText());
    }
}

}  // namespace rtbench
