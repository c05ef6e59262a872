#include "bvh_build.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <chrono>
#include <functional>
#include <new>

#include "core/error.h"
#include "flat_bvh_writer.h"

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

// Embree's tree, written depth first into the flat layout.
struct Flattener {
    FlatBvhWriter& writer;

    std::uint32_t inner(const BuildInner& node, double nodeArea, unsigned depth) {
        const std::uint32_t index = writer.openInner(nodeArea, depth);
        std::uint32_t refs[2];
        glm::vec3 lo[2], hi[2];
        for (int c = 0; c < 2; ++c) {
            const RTCBounds& b = node.bounds[c];
            lo[c] = glm::vec3(b.lower_x, b.lower_y, b.lower_z);
            hi[c] = glm::vec3(b.upper_x, b.upper_y, b.upper_z);
            refs[c] = child(node.children[c], boxArea(lo[c], hi[c]), depth + 1);
        }
        writer.closeInner(index, lo, hi, refs);
        return index;
    }

    std::uint32_t child(const BuildNode* node, double childArea, unsigned depth) {
        if (!node) throw Error("BVH: Embree returned an incomplete tree");
        if (!node->leaf) return inner(*static_cast<const BuildInner*>(node), childArea, depth);
        const auto* leaf = static_cast<const BuildLeaf*>(node);
        return writer.leaf(leaf->ids(), leaf->count, childArea, depth);
    }
};

}  // namespace

FlatBvh buildBvh(const TriangleMesh& mesh, const BvhBuildOptions& options) {
    refuseBvhInput(mesh, options.maxLeafSize);
    const auto start = std::chrono::steady_clock::now();
    FlatBvh out = startFlatBvh(mesh);
    std::vector<RTCBuildPrimitive> prims(out.triangles.size());
    for (std::size_t i = 0; i < out.triangles.size(); ++i) {
        const Bounds3 b = triangleBox(out.triangles[i]);
        prims[i] = {b.min.x, b.min.y, b.min.z, 0u, b.max.x, b.max.y, b.max.z, std::uint32_t(i)};
    }

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
    FlatBvhWriter writer(out, options.traversalCost, options.intersectionCost);
    auto release = [&] {
        rtcReleaseBVH(bvh);
        rtcReleaseDevice(device);
    };
    try {
        const BuildNode* root = static_cast<const BuildNode*>(rtcBuildBVH(&args));
        const RTCError error = rtcGetDeviceError(device);
        if (!root || error != RTC_ERROR_NONE)
            throw Error("BVH: rtcBuildBVH failed (RTCError " + std::to_string(int(error)) + ")");
        if (root->leaf) {
            const auto* leaf = static_cast<const BuildLeaf*>(root);
            writer.leafRoot(leaf->ids(), leaf->count);
        } else {
            Flattener{writer}.inner(*static_cast<const BuildInner*>(root), writer.rootArea(), 0);
        }
    } catch (...) {
        release();
        throw;
    }
    release();
    writer.finish(start);
    return out;
}

}  // namespace rtbench
