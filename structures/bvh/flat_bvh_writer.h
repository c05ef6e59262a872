// Writes a binary tree into the flat layout of bvh_layout.h, depth first from the root (child 0
// first), keeping BvhStats as it goes; the one place the layout's limits are checked. Each BVH
// builder (Embree's, the median split) walks its own tree through it.
#pragma once
#include <chrono>
#include <cstdint>

#include "bvh_build.h"

namespace rtbench {

// The box of a triangle's three vertices.
Bounds3 triangleBox(const gpu::Triangle& t);

// Surface area of a box (0 for an empty or inverted one), in double.
double boxArea(glm::vec3 lo, glm::vec3 hi);

// Throws rtbench::Error for an empty mesh, a leaf size outside 1..kBvhMaxLeafSize or a scene out
// of range; a builder calls it before its build time starts (as Embree's own build time leaves it out).
void refuseBvhInput(const TriangleMesh& mesh, unsigned maxLeafSize);

// A FlatBvh of the mesh with no nodes yet: its triangles, lattice and scene box.
FlatBvh startFlatBvh(const TriangleMesh& mesh);

class FlatBvhWriter {
public:
    // SAH costs: of visiting a node and of one ray-triangle test (BvhStats::sahCost).
    FlatBvhWriter(FlatBvh& out, float traversalCost, float intersectionCost);
    double rootArea() const { return rootArea_; }  // the scene box's
    // A leaf of `count` triangle ids (in ascending order) whose box has surface `area`, `depth`
    // edges below the root: its reference.
    std::uint32_t leaf(const std::uint32_t* ids, std::uint32_t count, double area, unsigned depth);
    // An inner node, appended before its children: its index, to close once they are written.
    std::uint32_t openInner(double area, unsigned depth);
    void closeInner(std::uint32_t index, const glm::vec3 lo[2], const glm::vec3 hi[2], const std::uint32_t refs[2]);
    // A tree that is a single leaf: the root is an inner node with that leaf its only child.
    void leafRoot(const std::uint32_t* ids, std::uint32_t count);
    // The totals (references, bytes, build time from `start`) once the tree is written.
    void finish(std::chrono::steady_clock::time_point start);

private:
    FlatBvh& out_;
    float traversalCost_, intersectionCost_;
    double rootArea_;
    double areaDivisor_;  // the root's area, at least 1e-300 (SAH costs are relative to it)
};

}  // namespace rtbench
