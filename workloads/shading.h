// The shading pass (Purcell et al. 2002 §3's shading kernel): the rays a generation's hits make,
// by one rule of kernels/shading.glsl (rtShade: a shadow ray, a mirror reflection, diffuse rays).
// The CPU runs it to make what a run traces (the workload), the device runs kernels/shading.comp,
// and the two must agree bit for bit, generation by generation (checkShadingOnDevice).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "device/vulkan_context.h"
#include "kernels/gpu_layout.h"
#include "structures/mesh.h"

namespace rtbench {

// A pass's rule: gpu::kShade*, the rays each hit makes (fan-out) and the bounce and seed of the
// random numbers of diffuse rays, the point light of shadow rays, the tMax of diffuse rays.
gpu::ShadingParams shadowPass(glm::vec3 light);
gpu::ShadingParams mirrorPass();
gpu::ShadingParams refractPass(float ior);
gpu::ShadingParams diffusePass(std::uint32_t fanOut, std::uint32_t bounce, std::uint32_t seed, float tMax);

// The rays a pass made, in the order of their parents and, per parent, of its slots.
struct ShadedRays {
    std::vector<gpu::Ray> rays;
    std::vector<std::uint32_t> parents;  // index of each ray's parent in the generation shaded
    std::vector<std::uint32_t> paths;    // each ray's path: its parent's path * fan-out + its slot
};

// The pass over rays `rays` with hits `hits` on `scene`. paths[i] is ray i's path (the key of
// its random numbers); empty: ray i's path is i (the camera rays: a path per pixel). Misses make
// no ray. Throws when parents x fan-out exceed 32-bit slots.
ShadedRays shadeOnCpu(const TriangleMesh& scene, const std::vector<gpu::Ray>& rays, const std::vector<gpu::HitRecord>& hits,
                      const std::vector<std::uint32_t>& paths, const gpu::ShadingParams& pass);

// The same on the device (kernels/shading.comp), the scene as its float triangles
// (methods/triangle_store.h floatTriangles), uploaded for the call; `ms` gets the dispatch's GPU
// time (-1 without timestamps).
ShadedRays shadeOnDevice(VulkanContext& vk, unsigned workgroupSize, const std::vector<gpu::Triangle>& triangles,
                         const std::vector<gpu::Ray>& rays, const std::vector<gpu::HitRecord>& hits,
                         const std::vector<std::uint32_t>& paths, const gpu::ShadingParams& pass, double& ms);

// Rays of `device` that differ from `cpu`'s (in their bits, their parent or their path), plus the
// difference in count; `first` describes the first.
std::uint64_t shadedMismatches(const ShadedRays& device, const ShadedRays& cpu, std::string& first);

}  // namespace rtbench
