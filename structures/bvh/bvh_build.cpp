#include "bvh_build.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <chrono>
#include <functional>
#include <new>

#include "structures/triangle_store.h"
#include "core/error.h"
#include "scene/scene_limits.h"

namespace rtbench {

namespace {

// Embree's tree, as its callbacks build it (memory from rtcThreadLocalAlloc, freed with the BVH).
struct BuildNode {
    bool leaf;
};
struct BuildInner : BuildNode {
    BuildNode* children[2];
    RTCBounds bounds[2];
};
struct BuildLeaf : BuildNode {
    std::uint32_t count;
    // The `count` triangle ids, allocated right after the struct.
    std::uint32_t* ids() { return reinterpret_cast<std::uint32_t*>(this + 1); }
    const std::uint32_t* ids() const { return reinterpret_cast<const std::uint32_t*>(this + 1); }
};

void* createInner(RTCThreadLocalAllocator alloc, unsigned int childCount, void*) {
    if (childCount != 2) return nullptr;  // maxBranchingFactor is 2
    auto* node = new (rtcThreadLocalAlloc(alloc, sizeof(BuildInner), 16)) BuildInner;
    node->leaf = false;
    node->children[0] = node->children[1] = nullptr;
    return node;
}

void setChildren(void* nodePtr, void** children, unsigned int childCount, void*) {
    auto* node = static_cast<BuildInner*>(nodePtr);
    for (unsigned i = 0; i < childCount && i < 2; ++i) node->children[i] = static_cast<BuildNode*>(children[i]);
}

void setBounds(void* nodePtr, const RTCBounds** bounds, unsigned int childCount, void*) {
    auto* node = static_cast<BuildInner*>(nodePtr);
    for (unsigned i = 0; i < childCount && i < 2; ++i) node->bounds[i] = *bounds[i];
}

void* createLeaf(RTCThreadLocalAllocator alloc, const RTCBuildPrimitive* prims, size_t count, void*) {
    const std::size_t bytes = sizeof(BuildLeaf) + sizeof(std::uint32_t) * count;
    auto* leaf = new (rtcThreadLocalAlloc(alloc, bytes, 16)) BuildLeaf;
    leaf->leaf = true;
    leaf->count = std::uint32_t(count);
    std::uint32_t* ids = leaf->ids();
    for (std::size_t i = 0; i < count; ++i) ids[i] = prims[i].primID;
    std::sort(ids, ids + count);  // Embree's threads may hand them over in any order
    return leaf;
}

double area(glm::vec3 lo, glm::vec3 hi) {
    const glm::dvec3 e = glm::max(glm::dvec3(hi) - glm::dvec3(lo), glm::dvec3(0.0));
    return 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
}

struct Flattener {
    FlatBvh& out;
    const BvhBuildOptions& options;
    double rootArea = 1.0;

    std::uint32_t leafRef(const BuildLeaf& leaf, double leafArea, unsigned depth) {
        if (leaf.count == 0 || leaf.count > gpu::kBvhMaxLeafSize)
            throw Error("BVH: Embree made a leaf of " + std::to_string(leaf.count) + " triangles (the layout holds 1 to " +
                        std::to_string(gpu::kBvhMaxLeafSize) + ")");
        const std::uint64_t first = out.triangleList.size();
        if (first + leaf.count > gpu::kBvhMaxReferences)
            throw Error("BVH: more than " + std::to_string(gpu::kBvhMaxReferences) +
                        " triangle references (the layout's 24-bit leaf offsets)");
        out.triangleList.insert(out.triangleList.end(), leaf.ids(), leaf.ids() + leaf.count);
        out.stats.leaves += 1;
        out.stats.largestLeaf = std::max(out.stats.largestLeaf, unsigned(leaf.count));
        out.stats.depth = std::max(out.stats.depth, depth);
        out.stats.sahCost += options.intersectionCost * leaf.count * leafArea / rootArea;
        return gpu::kBvhLeaf | ((leaf.count - 1) << 24) | std::uint32_t(first);
    }

    // Appends an inner node and its subtree depth first; returns its index.
    std::uint32_t inner(const BuildInner& node, double nodeArea, unsigned depth) {
        if (depth >= gpu::kBvhStackSize)
            throw Error("BVH: deeper than the traversal stack of " + std::to_string(gpu::kBvhStackSize) + " entries");
        const std::uint32_t index = std::uint32_t(out.nodes.size());
        out.nodes.emplace_back();
        out.stats.innerNodes += 1;
        out.stats.sahCost += options.traversalCost * nodeArea / rootArea;
        std::uint32_t refs[2];
        glm::vec3 lo[2], hi[2];
        for (int c = 0; c < 2; ++c) {
            const RTCBounds& b = node.bounds[c];
            lo[c] = glm::vec3(b.lower_x, b.lower_y, b.lower_z);
            hi[c] = glm::vec3(b.upper_x, b.upper_y, b.upper_z);
            refs[c] = child(node.children[c], area(lo[c], hi[c]), depth + 1);
        }
        gpu::BvhNode& n = out.nodes[index];
        n.min0 = glm::vec4(lo[0], 0.0f), n.max0 = glm::vec4(hi[0], 0.0f);
        n.min1 = glm::vec4(lo[1], 0.0f), n.max1 = glm::vec4(hi[1], 0.0f);
        n.children = glm::uvec4(refs[0], refs[1], 0u, 0u);
        return index;
    }

    std::uint32_t child(const BuildNode* node, double childArea, unsigned depth) {
        if (!node) throw Error("BVH: Embree returned an incomplete tree");
        if (node->leaf) return leafRef(*static_cast<const BuildLeaf*>(node), childArea, depth);
        return inner(*static_cast<const BuildInner*>(node), childArea, depth);
    }
};

}  // namespace

FlatBvh buildBvh(const TriangleMesh& mesh, const BvhBuildOptions& options) {
    if (mesh.triangles.empty()) throw Error("BVH: the scene has no triangles");
    if (options.maxLeafSize < 1 || options.maxLeafSize > gpu::kBvhMaxLeafSize)
        throw Error("BVH: leaf size " + std::to_string(options.maxLeafSize) + " outside 1.." +
                    std::to_string(gpu::kBvhMaxLeafSize));
    validateSceneRange(mesh);
    const auto start = std::chrono::steady_clock::now();
    FlatBvh out;
    out.lattice = mesh.lattice;
    out.triangles.reserve(mesh.triangles.size());
    Bounds3 box;
    std::vector<RTCBuildPrimitive> prims(mesh.triangles.size());
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
        const glm::uvec3 t = mesh.triangles[i];
        const glm::vec3 a = mesh.vertices[t.x], b = mesh.vertices[t.y], c = mesh.vertices[t.z];
        out.triangles.push_back({glm::vec4(a, 0.0f), glm::vec4(b, 0.0f), glm::vec4(c, 0.0f)});
        const glm::vec3 lo = glm::min(a, glm::min(b, c)), hi = glm::max(a, glm::max(b, c));
        box.extend(lo), box.extend(hi);
        prims[i] = {lo.x, lo.y, lo.z, 0u, hi.x, hi.y, hi.z, std::uint32_t(i)};
    }
    out.params.boundsMin = glm::vec4(box.min, 0.0f);
    out.params.boundsMax = glm::vec4(box.max, 0.0f);

    RTCDevice device = rtcNewDevice(options.embreeConfig.empty() ? nullptr : options.embreeConfig.c_str());
    if (!device) throw Error("BVH: rtcNewDevice(\"" + options.embreeConfig + "\") failed");
    RTCBVH bvh = rtcNewBVH(device);
    RTCBuildArguments args = rtcDefaultBuildArguments();
    args.buildQuality = options.quality == "low" ? RTC_BUILD_QUALITY_LOW : RTC_BUILD_QUALITY_MEDIUM;
    args.maxBranchingFactor = 2;
    args.maxDepth = gpu::kBvhStackSize;
    args.minLeafSize = 1;
    args.maxLeafSize = options.maxLeafSize;
    args.traversalCost = options.traversalCost;
    args.intersectionCost = options.intersectionCost;
    args.bvh = bvh;
    args.primitives = prims.data();
    args.primitiveCount = prims.size();
    args.primitiveArrayCapacity = prims.size();
    args.createNode = createInner;
    args.setNodeChildren = setChildren;
    args.setNodeBounds = setBounds;
    args.createLeaf = createLeaf;
    auto release = [&] {
        rtcReleaseBVH(bvh);
        rtcReleaseDevice(device);
    };
    try {
        const BuildNode* root = static_cast<const BuildNode*>(rtcBuildBVH(&args));
        const RTCError error = rtcGetDeviceError(device);
        if (!root || error != RTC_ERROR_NONE)
            throw Error("BVH: rtcBuildBVH failed (RTCError " + std::to_string(int(error)) + ")");
        Flattener flat{out, options, std::max(area(box.min, box.max), 1e-300)};
        if (root->leaf) {
            // A scene of a single leaf: the root is an inner node with one child.
            out.nodes.emplace_back();
            out.stats.innerNodes = 1;
            out.stats.sahCost = options.traversalCost;
            const std::uint32_t ref = flat.leafRef(*static_cast<const BuildLeaf*>(root), area(box.min, box.max), 1);
            gpu::BvhNode& n = out.nodes[0];
            n.min0 = glm::vec4(box.min, 0.0f), n.max0 = glm::vec4(box.max, 0.0f);
            n.min1 = n.max1 = glm::vec4(0.0f);
            n.children = glm::uvec4(ref, gpu::kBvhNone, 0u, 0u);
        } else {
            flat.inner(*static_cast<const BuildInner*>(root), area(box.min, box.max), 0);
        }
    } catch (...) {
        release();
        throw;
    }
    release();
    out.stats.references = out.triangleList.size();
    out.stats.bytes = out.nodes.size() * sizeof(gpu::BvhNode) + out.triangleList.size() * 4 +
                      out.triangles.size() * triangleVertexBytes(out.lattice);
    out.stats.buildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return out;
}

}  // namespace rtbench
