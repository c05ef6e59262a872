#include "flat_bvh_writer.h"

#include <algorithm>
#include <string>

#include "core/error.h"
#include "scene/scene_limits.h"
#include "structures/triangle_store.h"

namespace rtbench {

Bounds3 triangleBox(const gpu::Triangle& t) {
    const glm::vec3 a(t.v0), b(t.v1), c(t.v2);
    return {glm::min(a, glm::min(b, c)), glm::max(a, glm::max(b, c))};
}

double boxArea(glm::vec3 lo, glm::vec3 hi) {
    const glm::dvec3 e = glm::max(glm::dvec3(hi) - glm::dvec3(lo), glm::dvec3(0.0));
    return 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
}

void refuseBvhInput(const TriangleMesh& mesh, unsigned maxLeafSize) {
    if (mesh.triangles.empty()) throw Error("BVH: the scene has no triangles");
    if (maxLeafSize < 1 || maxLeafSize > gpu::kBvhMaxLeafSize)
        throw Error("BVH: leaf size " + std::to_string(maxLeafSize) + " outside 1.." + std::to_string(gpu::kBvhMaxLeafSize));
    validateSceneRange(mesh);
}

FlatBvh startFlatBvh(const TriangleMesh& mesh) {
    FlatBvh out;
    out.lattice = mesh.lattice;
    out.triangles.reserve(mesh.triangles.size());
    Bounds3 box;
    for (const glm::uvec3 t : mesh.triangles) {
        const glm::vec3 a = mesh.vertices[t.x], b = mesh.vertices[t.y], c = mesh.vertices[t.z];
        out.triangles.push_back({glm::vec4(a, 0.0f), glm::vec4(b, 0.0f), glm::vec4(c, 0.0f)});
        const Bounds3 own = triangleBox(out.triangles.back());
        box.extend(own.min), box.extend(own.max);
    }
    out.params.boundsMin = glm::vec4(box.min, 0.0f);
    out.params.boundsMax = glm::vec4(box.max, 0.0f);
    return out;
}

FlatBvhWriter::FlatBvhWriter(FlatBvh& out, float traversalCost, float intersectionCost)
    : out_(out), traversalCost_(traversalCost), intersectionCost_(intersectionCost),
      rootArea_(boxArea(glm::vec3(out.params.boundsMin), glm::vec3(out.params.boundsMax))),
      areaDivisor_(std::max(rootArea_, 1e-300)) {}

std::uint32_t FlatBvhWriter::leaf(const std::uint32_t* ids, std::uint32_t count, double area, unsigned depth) {
    if (count == 0 || count > gpu::kBvhMaxLeafSize)
        throw Error("BVH: the builder made a leaf of " + std::to_string(count) + " triangles (the layout holds 1 to " +
                    std::to_string(gpu::kBvhMaxLeafSize) + ")");
    const std::uint64_t first = out_.triangleList.size();
    if (first + count > gpu::kBvhMaxReferences)
        throw Error("BVH: more than " + std::to_string(gpu::kBvhMaxReferences) +
                    " triangle references (the layout's 24-bit leaf offsets)");
    out_.triangleList.insert(out_.triangleList.end(), ids, ids + count);
    out_.stats.leaves += 1;
    out_.stats.largestLeaf = std::max(out_.stats.largestLeaf, unsigned(count));
    out_.stats.depth = std::max(out_.stats.depth, depth);
    out_.stats.sahCost += intersectionCost_ * count * area / areaDivisor_;
    return gpu::kBvhLeaf | ((count - 1) << 24) | std::uint32_t(first);
}

std::uint32_t FlatBvhWriter::openInner(double area, unsigned depth) {
    if (depth >= gpu::kBvhStackSize)
        throw Error("BVH: deeper than the traversal stack of " + std::to_string(gpu::kBvhStackSize) + " entries");
    const std::uint32_t index = std::uint32_t(out_.nodes.size());
    out_.nodes.emplace_back();
    out_.stats.innerNodes += 1;
    out_.stats.sahCost += traversalCost_ * area / areaDivisor_;
    return index;
}

void FlatBvhWriter::closeInner(std::uint32_t index, const glm::vec3 lo[2], const glm::vec3 hi[2], const std::uint32_t refs[2]) {
    gpu::BvhNode& n = out_.nodes[index];
    n.min0 = glm::vec4(lo[0], 0.0f), n.max0 = glm::vec4(hi[0], 0.0f);
    n.min1 = glm::vec4(lo[1], 0.0f), n.max1 = glm::vec4(hi[1], 0.0f);
    n.children = glm::uvec4(refs[0], refs[1], 0u, 0u);
}

void FlatBvhWriter::leafRoot(const std::uint32_t* ids, std::uint32_t count) {
    const glm::vec3 lo(out_.params.boundsMin), hi(out_.params.boundsMax);
    out_.nodes.emplace_back();
    out_.stats.innerNodes = 1;
    out_.stats.sahCost = traversalCost_;
    const std::uint32_t ref = leaf(ids, count, boxArea(lo, hi), 1);
    gpu::BvhNode& n = out_.nodes[0];
    n.min0 = glm::vec4(lo, 0.0f), n.max0 = glm::vec4(hi, 0.0f);
    n.min1 = n.max1 = glm::vec4(0.0f);
    n.children = glm::uvec4(ref, gpu::kBvhNone, 0u, 0u);
}

void FlatBvhWriter::finish(std::chrono::steady_clock::time_point start) {
    out_.stats.references = out_.triangleList.size();
    out_.stats.bytes = out_.nodes.size() * sizeof(gpu::BvhNode) + out_.triangleList.size() * 4 +
                       out_.triangles.size() * triangleVertexBytes(out_.lattice);
    out_.stats.buildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace rtbench
