// The shading pass (Purcell et al. 2002 §3's shading kernel): the rays a generation's hits make,
// by one rule of kernels/shading.glsl (rtShade: shadow rays toward each light, a mirror reflection,
// a refraction, Whitted's reflection and refraction by material, diffuse rays).
// The CPU runs it to make what a run traces (the workload), the device runs kernels/shading.comp,
// and the two must agree bit for bit, generation by generation (checkShadingOnDevice).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "device/vulkan_context.h"
#include "kernels/gpu_layout.h"
#include "scene/mesh.h"

namespace rtbench {

// A pass's rule: gpu::kShade*, the rays each hit makes (fan-out) and the bounce and seed of the
// random numbers of diffuse rays, the tMax of diffuse rays. A shadow pass makes a ray toward
// each of `lights` lights (Surfaces::lights); a specular pass (Whitted) a reflection and a
// refraction by each surface's material.
gpu::ShadingParams shadowPass(std::uint32_t lights = 1);
gpu::ShadingParams mirrorPass();
gpu::ShadingParams refractPass(float ior);
gpu::ShadingParams specularPass();
gpu::ShadingParams diffusePass(std::uint32_t fanOut, std::uint32_t bounce, std::uint32_t seed, float tMax);

gpu::Material diffuseMaterial(glm::vec3 colour = glm::vec3(0.8f));
gpu::Material mirrorMaterial(float reflectance, glm::vec3 colour = glm::vec3(0.8f));
gpu::Material glassMaterial(float ior);

// What a pass reads of the scene beside its triangles: each triangle's material and the point
// lights. By default every surface diffuse and no light (the ray types whose rule ignores both).
struct Surfaces {
    std::vector<gpu::Material> materials = {diffuseMaterial()};  // at least one
    std::vector<std::uint32_t> materialOf;  // per triangle, into materials; empty: every triangle materials[0]
    std::vector<glm::vec3> lights;          // a shadow pass's slot l goes toward lights[l]
};

// A generation of rays as a pass reads it: the rays, their hits, each ray's path (the key of its
// random numbers; empty: ray i's path is i, the camera rays' path per pixel) and weight (the
// fraction of its radiance the pixel gets; empty: 1, the camera rays).
struct ShadingInput {
    const std::vector<gpu::Ray>& rays;
    const std::vector<gpu::HitRecord>& hits;
    const std::vector<std::uint32_t>& paths;
    const std::vector<float>& weights;
};

// The rays a pass made, in the order of their parents and, per parent, of its slots.
struct ShadedRays {
    std::vector<gpu::Ray> rays;
    std::vector<std::uint32_t> parents;  // index of each ray's parent in the generation shaded
    std::vector<std::uint32_t> paths;    // each ray's path: its parent's path * fan-out + its slot
    std::vector<float> weights;          // each ray's weight (kernels/shading.glsl rtShade)
};

// The pass over `in` on `scene` and `surfaces`. Misses make no ray. Throws when parents x fan-out
// exceed 32-bit slots, or a shadow pass has more slots than lights.
ShadedRays shadeOnCpu(const TriangleMesh& scene, const Surfaces& surfaces, const ShadingInput& in,
                      const gpu::ShadingParams& pass);

// The same on the device (kernels/shading.comp), the scene as its float triangles
// (structures/triangle_store.h floatTriangles), uploaded for the call; `ms` gets the dispatch's GPU
// time (-1 without timestamps).
ShadedRays shadeOnDevice(VulkanContext& vk, unsigned workgroupSize, const std::vector<gpu::Triangle>& triangles,
                         const Surfaces& surfaces, const ShadingInput& in, const gpu::ShadingParams& pass, double& ms);

// Rays of `device` that differ from `cpu`'s (in their bits, their parent, their path or their
// weight), plus the difference in count; `first` describes the first.
std::uint64_t shadedMismatches(const ShadedRays& device, const ShadedRays& cpu, std::string& first);

}  // namespace rtbench
