#include "shading.h"

#include <cstring>
#include <limits>

#include "device/embedded_kernels.h"
#include "core/error.h"
#include "rays/shading_reference.h"

namespace rtbench {

gpu::ShadingParams shadowPass(std::uint32_t lights) {
    gpu::ShadingParams p{};
    p.pass = {0, gpu::kShadeShadow, lights, 0};
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
    p.values = glm::vec4(ior, 0.0f, 0.0f, 0.0f);
    return p;
}

gpu::ShadingParams specularPass() {
    gpu::ShadingParams p{};
    p.pass = {0, gpu::kShadeSpecular, 2, 0};
    return p;
}

gpu::ShadingParams diffusePass(std::uint32_t fanOut, std::uint32_t bounce, std::uint32_t seed, float tMax) {
    gpu::ShadingParams p{};
    p.pass = {0, gpu::kShadeDiffuse, fanOut, bounce};
    p.seed = {seed, 0, 0, 0};
    p.values = glm::vec4(tMax, 0.0f, 0.0f, 0.0f);
    return p;
}

gpu::Material diffuseMaterial(glm::vec3 colour) {
    gpu::Material m{};
    m.kind = {gpu::kMaterialDiffuse, 0, 0, 0};
    m.colour = glm::vec4(colour, 0.0f);
    return m;
}

gpu::Material mirrorMaterial(float reflectance, glm::vec3 colour) {
    gpu::Material m = diffuseMaterial(colour);
    m.kind.x = gpu::kMaterialMirror;
    m.optics.x = reflectance;
    return m;
}

gpu::Material glassMaterial(float ior) {
    gpu::Material m = diffuseMaterial(glm::vec3(0.0f));
    m.kind.x = gpu::kMaterialGlass;
    m.optics.y = ior;
    return m;
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
                    const std::vector<float>& weights, const std::vector<std::uint32_t>& paths, std::uint32_t fanOut) {
    ShadedRays out;
    for (std::uint32_t slot = 0; slot < slots.size(); ++slot) {
        if (!made[slot]) continue;
        const std::uint32_t parent = slot / fanOut;
        out.rays.push_back(slots[slot]);
        out.parents.push_back(parent);
        out.paths.push_back((paths.empty() ? parent : paths[parent]) * fanOut + slot % fanOut);
        out.weights.push_back(weights[slot]);
    }
    return out;
}

// The pass's rule checked against what it reads: a shadow pass has a light for each slot, the
// materials cover the triangles.
void checkSurfaces(const Surfaces& surfaces, std::size_t triangles, const gpu::ShadingParams& pass) {
    if (pass.pass.y == gpu::kShadeShadow && surfaces.lights.size() < pass.pass.z)
        throw Error("a shadow pass of " + std::to_string(pass.pass.z) + " rays per hit has " +
                    std::to_string(surfaces.lights.size()) + " lights");
    if (surfaces.materials.empty()) throw Error("a shading pass with no material");
    if (!surfaces.materialOf.empty() && surfaces.materialOf.size() != triangles)
        throw Error("a shading pass with materials for " + std::to_string(surfaces.materialOf.size()) + " of " +
                    std::to_string(triangles) + " triangles");
    for (std::uint32_t m : surfaces.materialOf)
        if (m >= surfaces.materials.size()) throw Error("a triangle's material " + std::to_string(m) + " is not among the " +
                                                        std::to_string(surfaces.materials.size()) + " materials");
}

}  // namespace

ShadedRays shadeOnCpu(const TriangleMesh& scene, const Surfaces& surfaces, const ShadingInput& in,
                      const gpu::ShadingParams& pass) {
    checkSurfaces(surfaces, scene.triangles.size(), pass);
    gpu::ShadingParams p = pass;
    p.pass.x = std::uint32_t(in.rays.size());
    const std::uint32_t fanOut = p.pass.z;
    std::vector<gpu::Ray> slots(slotCount(in.rays.size(), p));
    std::vector<std::uint32_t> made(slots.size(), 0);
    std::vector<float> weights(slots.size(), 0.0f);
    shadingref::ShadingKernels k{};
    for (std::uint32_t i = 0; i < in.rays.size(); ++i) {
        const gpu::HitRecord& h = in.hits.at(i);
        if (h.primitive == gpu::kNoHit) continue;
        const glm::uvec3 t = scene.triangles.at(h.primitive);
        const gpu::Material& m = surfaces.materials[surfaces.materialOf.empty() ? 0 : surfaces.materialOf[h.primitive]];
        for (std::uint32_t s = 0; s < fanOut; ++s) {
            const glm::vec3 light = p.pass.y == gpu::kShadeShadow ? surfaces.lights[s] : glm::vec3(0.0f);
            made[i * fanOut + s] =
                k.rtShade(p, m, light, scene.vertices[t.x], scene.vertices[t.y], scene.vertices[t.z], h.u, h.v,
                          glm::vec3(in.rays[i].directionTMax), in.paths.empty() ? i : in.paths[i], s,
                          in.weights.empty() ? 1.0f : in.weights[i], slots[i * fanOut + s], weights[i * fanOut + s]);
        }
    }
    return keepMade(slots, made, weights, in.paths, fanOut);
}

ShadedRays shadeOnDevice(VulkanContext& vk, unsigned workgroupSize, const std::vector<gpu::Triangle>& triangles,
                         const Surfaces& surfaces, const ShadingInput& in, const gpu::ShadingParams& pass, double& ms) {
    checkSurfaces(surfaces, triangles.size(), pass);
    gpu::ShadingParams p = pass;
    p.pass.x = std::uint32_t(in.rays.size());
    const std::uint64_t slots = slotCount(in.rays.size(), p);
    // What the CPU takes as given when absent: path i, weight 1, material 0, and a light for a
    // pass of none (never read: a buffer is never empty).
    std::vector<std::uint32_t> pathOf = in.paths;
    if (pathOf.empty())
        for (std::uint32_t i = 0; i < in.rays.size(); ++i) pathOf.push_back(i);
    std::vector<float> weightOf = in.weights;
    if (weightOf.empty()) weightOf.assign(in.rays.size(), 1.0f);
    std::vector<std::uint32_t> materialOf = surfaces.materialOf;
    if (materialOf.empty()) materialOf.assign(triangles.size(), 0);
    std::vector<glm::vec4> lights;
    for (const glm::vec3& l : surfaces.lights) lights.emplace_back(l, 0.0f);
    if (lights.empty()) lights.emplace_back(0.0f);
    // Binding slots kShadingBinding*, in order: what each holds and its bytes (at least 4: a buffer is never empty).
    struct Slot {
        std::string what;
        std::uint64_t bytes;
        const void* upload;  // null: written by the pass
    };
    const std::vector<Slot> bindings = {
        {"shading: parent rays", in.rays.size() * sizeof(gpu::Ray), in.rays.data()},
        {"shading: parent hits", in.hits.size() * sizeof(gpu::HitRecord), in.hits.data()},
        {"shading: paths", pathOf.size() * sizeof(std::uint32_t), pathOf.data()},
        {"shading: triangles", triangles.size() * sizeof(gpu::Triangle), triangles.data()},
        {"shading: rays made", slots * sizeof(gpu::Ray), nullptr},
        {"shading: made flags", slots * sizeof(std::uint32_t), nullptr},
        {"shading: material of each triangle", materialOf.size() * sizeof(std::uint32_t), materialOf.data()},
        {"shading: materials", surfaces.materials.size() * sizeof(gpu::Material), surfaces.materials.data()},
        {"shading: lights", lights.size() * sizeof(glm::vec4), lights.data()},
        {"shading: parent weights", weightOf.size() * sizeof(float), weightOf.data()},
        {"shading: weights made", slots * sizeof(float), nullptr}};
    static_assert(gpu::kShadingBindingCount == 11, "a binding for every slot");
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
    for (const Slot& b : bindings) {
        buffers.push_back(vk.createStorageBuffer(std::max<std::uint64_t>(b.bytes, 4), b.what));
        if (b.upload) vk.upload(buffers.back(), b.upload, b.bytes);
    }
    pipeline = vk.createComputePipeline(embeddedKernel("shading"), gpu::kShadingBindingCount, sizeof(gpu::ShadingParams),
                                        workgroupSize, {{gpu::kSpecWorkgroupSize, workgroupSize}});
    std::vector<const Buffer*> bound;
    for (const Buffer& b : buffers) bound.push_back(&b);
    ms = vk.dispatch(pipeline, bound, &p, slots);
    std::vector<gpu::Ray> made(slots);
    std::vector<std::uint32_t> flags(slots);
    std::vector<float> weights(slots);
    vk.download(buffers[gpu::kShadingBindingRays], made.data(), slots * sizeof(gpu::Ray));
    vk.download(buffers[gpu::kShadingBindingMade], flags.data(), slots * sizeof(std::uint32_t));
    vk.download(buffers[gpu::kShadingBindingMadeWeights], weights.data(), slots * sizeof(float));
    return keepMade(made, flags, weights, in.paths, p.pass.z);
}

std::uint64_t shadedMismatches(const ShadedRays& device, const ShadedRays& cpu, std::string& first) {
    const std::size_t n = std::min(device.rays.size(), cpu.rays.size());
    std::uint64_t differing = std::max(device.rays.size(), cpu.rays.size()) - n;
    for (std::size_t i = 0; i < n; ++i) {
        if (std::memcmp(&device.rays[i], &cpu.rays[i], sizeof(gpu::Ray)) == 0 && device.parents[i] == cpu.parents[i] &&
            device.paths[i] == cpu.paths[i] && std::memcmp(&device.weights[i], &cpu.weights[i], sizeof(float)) == 0)
            continue;
        if (differing++ == 0 && first.empty())
            first = "ray " + std::to_string(i) + " (parent " + std::to_string(cpu.parents[i]) + ")";
    }
    if (differing && first.empty())
        first = std::to_string(device.rays.size()) + " rays made on the device, " + std::to_string(cpu.rays.size()) + " on the CPU";
    return differing;
}

}  // namespace rtbench
