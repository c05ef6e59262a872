#include "shading.h"

#include <cstring>
#include <limits>

#include "device/embedded_kernels.h"
#include "structures/error.h"
#include "workloads/shading_reference.h"

namespace rtbench {

gpu::ShadingParams shadowPass(glm::vec3 light) {
    gpu::ShadingParams p{};
    p.pass = {0, gpu::kShadeShadow, 1, 0};
    p.light = glm::vec4(light, 0.0f);
    return p;
}

gpu::ShadingParams mirrorPass() {
    gpu::ShadingParams p{};
    p.pass = {0, gpu::kShadeMirror, 1, 0};
    return p;
}

gpu::ShadingParams refractPass(float ior) {
    gpu::ShadingParams p{};
    p.pass = {0, gpu::kShadeRefract, 1, 0};
    p.light = glm::vec4(0.0f, 0.0f, 0.0f, ior);
    return p;
}

gpu::ShadingParams diffusePass(std::uint32_t fanOut, std::uint32_t bounce, std::uint32_t seed, float tMax) {
    gpu::ShadingParams p{};
    p.pass = {0, gpu::kShadeDiffuse, fanOut, bounce};
    p.seed = {seed, 0, 0, 0};
    p.light = glm::vec4(0.0f, 0.0f, 0.0f, tMax);
    return p;
}

namespace {

std::uint64_t slotCount(std::size_t parents, const gpu::ShadingParams& pass) {
    const std::uint64_t slots = std::uint64_t(parents) * pass.pass.z;
    if (pass.pass.z == 0 || slots > std::numeric_limits<std::uint32_t>::max())
        throw Error("a shading pass of " + std::to_string(parents) + " rays x " + std::to_string(pass.pass.z) +
                    " rays each: " + std::to_string(slots) + " rays, over the 2^32 - 1 a pass can number");
    return slots;
}

// The made slots, in slot order: what both passes return.
ShadedRays keepMade(const std::vector<gpu::Ray>& slots, const std::vector<std::uint32_t>& made,
                    const std::vector<std::uint32_t>& paths, std::uint32_t fanOut) {
    ShadedRays out;
    for (std::uint32_t slot = 0; slot < slots.size(); ++slot) {
        if (!made[slot]) continue;
        const std::uint32_t parent = slot / fanOut;
        out.rays.push_back(slots[slot]);
        out.parents.push_back(parent);
        out.paths.push_back((paths.empty() ? parent : paths[parent]) * fanOut + slot % fanOut);
    }
    return out;
}

}  // namespace

ShadedRays shadeOnCpu(const TriangleMesh& scene, const std::vector<gpu::Ray>& rays, const std::vector<gpu::HitRecord>& hits,
                      const std::vector<std::uint32_t>& paths, const gpu::ShadingParams& pass) {
    gpu::ShadingParams p = pass;
    p.pass.x = std::uint32_t(rays.size());
    const std::uint32_t fanOut = p.pass.z;
    std::vector<gpu::Ray> slots(slotCount(rays.size(), p));
    std::vector<std::uint32_t> made(slots.size(), 0);
    shadingref::ShadingKernels k{};
    for (std::uint32_t i = 0; i < rays.size(); ++i) {
        const gpu::HitRecord& h = hits.at(i);
        if (h.primitive == gpu::kNoHit) continue;
        const glm::uvec3 t = scene.triangles.at(h.primitive);
        for (std::uint32_t s = 0; s < fanOut; ++s)
            made[i * fanOut + s] = k.rtShade(p, scene.vertices[t.x], scene.vertices[t.y], scene.vertices[t.z], h.u, h.v,
                                             glm::vec3(rays[i].directionTMax), paths.empty() ? i : paths[i], s,
                                             slots[i * fanOut + s]);
    }
    return keepMade(slots, made, paths, fanOut);
}

ShadedRays shadeOnDevice(VulkanContext& vk, unsigned workgroupSize, const std::vector<gpu::Triangle>& triangles,
                         const std::vector<gpu::Ray>& rays, const std::vector<gpu::HitRecord>& hits,
                         const std::vector<std::uint32_t>& paths, const gpu::ShadingParams& pass, double& ms) {
    gpu::ShadingParams p = pass;
    p.pass.x = std::uint32_t(rays.size());
    const std::uint64_t slots = slotCount(rays.size(), p);
    std::vector<std::uint32_t> pathOf = paths;
    if (pathOf.empty())
        for (std::uint32_t i = 0; i < rays.size(); ++i) pathOf.push_back(i);
    // Binding slots kShadingBinding*: what each holds and its bytes (at least 4: a buffer is never empty).
    const std::vector<std::pair<std::string, std::uint64_t>> sizes = {
        {"shading: parent rays", rays.size() * sizeof(gpu::Ray)},
        {"shading: parent hits", hits.size() * sizeof(gpu::HitRecord)},
        {"shading: paths", pathOf.size() * sizeof(std::uint32_t)},
        {"shading: triangles", triangles.size() * sizeof(gpu::Triangle)},
        {"shading: rays made", slots * sizeof(gpu::Ray)},
        {"shading: made flags", slots * sizeof(std::uint32_t)}};
    std::vector<Buffer> buffers;
    ComputePipeline pipeline{};
    // Whatever happens, the device memory and the pipeline go back.
    struct Release {
        VulkanContext& vk;
        std::vector<Buffer>& buffers;
        ComputePipeline& pipeline;
        ~Release() {
            for (Buffer& b : buffers) vk.destroy(b);
            vk.destroy(pipeline);
        }
    } release{vk, buffers, pipeline};
    for (const auto& [what, bytes] : sizes) buffers.push_back(vk.createStorageBuffer(std::max<std::uint64_t>(bytes, 4), what));
    vk.upload(buffers[gpu::kShadingBindingParents], rays.data(), sizes[0].second);
    vk.upload(buffers[gpu::kShadingBindingHits], hits.data(), sizes[1].second);
    vk.upload(buffers[gpu::kShadingBindingPaths], pathOf.data(), sizes[2].second);
    vk.upload(buffers[gpu::kShadingBindingTriangles], triangles.data(), sizes[3].second);
    pipeline = vk.createComputePipeline(embeddedKernel("shading"), gpu::kShadingBindingCount, sizeof(gpu::ShadingParams),
                                        workgroupSize, {{gpu::kSpecWorkgroupSize, workgroupSize}});
    std::vector<const Buffer*> bound;
    for (const Buffer& b : buffers) bound.push_back(&b);
    ms = vk.dispatch(pipeline, bound, &p, slots);
    std::vector<gpu::Ray> made(slots);
    std::vector<std::uint32_t> flags(slots);
    vk.download(buffers[gpu::kShadingBindingRays], made.data(), sizes[4].second);
    vk.download(buffers[gpu::kShadingBindingMade], flags.data(), sizes[5].second);
    return keepMade(made, flags, paths, p.pass.z);
}

std::uint64_t shadedMismatches(const ShadedRays& device, const ShadedRays& cpu, std::string& first) {
    const std::size_t n = std::min(device.rays.size(), cpu.rays.size());
    std::uint64_t differing = std::max(device.rays.size(), cpu.rays.size()) - n;
    for (std::size_t i = 0; i < n; ++i) {
        if (std::memcmp(&device.rays[i], &cpu.rays[i], sizeof(gpu::Ray)) == 0 && device.parents[i] == cpu.parents[i] &&
            device.paths[i] == cpu.paths[i])
            continue;
        if (differing++ == 0 && first.empty())
            first = "ray " + std::to_string(i) + " (parent " + std::to_string(cpu.parents[i]) + ")";
    }
    if (differing && first.empty())
        first = std::to_string(device.rays.size()) + " rays made on the device, " + std::to_string(cpu.rays.size()) + " on the CPU";
    return differing;
}

}  // namespace rtbench
