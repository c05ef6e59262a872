#include "median_bvh_build.h"

#include <algorithm>
#include <chrono>

#include "structures/bvh/flat_bvh_writer.h"

namespace rtbench {

namespace {

struct Primitive {
    glm::vec3 lo, hi, centroid;
    std::uint32_t id;
};

Bounds3 boxOf(const Primitive* first, const Primitive* last) {
    Bounds3 box;
    for (const Primitive* p = first; p != last; ++p) box.extend(p->lo), box.extend(p->hi);
    return box;
}

// The triangle ids of [first, last), ascending (a leaf's order).
std::vector<std::uint32_t> idsOf(const Primitive* first, const Primitive* last) {
    std::vector<std::uint32_t> ids;
    for (const Primitive* p = first; p != last; ++p) ids.push_back(p->id);
    std::sort(ids.begin(), ids.end());
    return ids;
}

struct MedianSplit {
    FlatBvhWriter& writer;
    unsigned maxLeafSize;

    // The subtree over [first, last), whose box has surface `area`: its reference.
    std::uint32_t node(Primitive* first, Primitive* last, double area, unsigned depth) {
        const std::size_t count = std::size_t(last - first);
        if (count <= maxLeafSize) {
            const std::vector<std::uint32_t> ids = idsOf(first, last);
            return writer.leaf(ids.data(), std::uint32_t(ids.size()), area, depth);
        }
        const std::uint32_t index = writer.openInner(area, depth);
        Primitive* middle = split(first, last);
        const Bounds3 boxes[2] = {boxOf(first, middle), boxOf(middle, last)};
        const glm::vec3 lo[2] = {boxes[0].min, boxes[1].min}, hi[2] = {boxes[0].max, boxes[1].max};
        const std::uint32_t refs[2] = {node(first, middle, boxArea(lo[0], hi[0]), depth + 1),
                                       node(middle, last, boxArea(lo[1], hi[1]), depth + 1)};
        writer.closeInner(index, lo, hi, refs);
        return index;
    }

    // Puts the lower half of the centroids along the longest axis of their box first (ties by
    // id, so the halves are the same on any machine); returns where the upper half starts.
    static Primitive* split(Primitive* first, Primitive* last) {
        Bounds3 centroids;
        for (const Primitive* p = first; p != last; ++p) centroids.extend(p->centroid);
        const glm::vec3 e = centroids.extent();
        const int axis = e.x >= e.y && e.x >= e.z ? 0 : e.y >= e.z ? 1 : 2;
        Primitive* middle = first + (last - first) / 2;
        std::nth_element(first, middle, last, [axis](const Primitive& a, const Primitive& b) {
            return a.centroid[axis] != b.centroid[axis] ? a.centroid[axis] < b.centroid[axis] : a.id < b.id;
        });
        return middle;
    }
};

}  // namespace

FlatBvh buildMedianBvh(const TriangleMesh& mesh, unsigned maxLeafSize) {
    refuseBvhInput(mesh, maxLeafSize);
    const auto start = std::chrono::steady_clock::now();
    FlatBvh out = startFlatBvh(mesh);
    std::vector<Primitive> prims(out.triangles.size());
    for (std::size_t i = 0; i < out.triangles.size(); ++i) {
        const Bounds3 b = triangleBox(out.triangles[i]);
        prims[i] = {b.min, b.max, 0.5f * (b.min + b.max), std::uint32_t(i)};
    }
    FlatBvhWriter writer(out, 1.0f, 1.0f);
    Primitive* first = prims.data();
    Primitive* last = first + prims.size();
    if (prims.size() <= maxLeafSize) {
        const std::vector<std::uint32_t> ids = idsOf(first, last);
        writer.leafRoot(ids.data(), std::uint32_t(ids.size()));
    } else {
        MedianSplit{writer, maxLeafSize}.node(first, last, writer.rootArea(), 0);
    }
    writer.finish(start);
    return out;
}

}  // namespace rtbench
