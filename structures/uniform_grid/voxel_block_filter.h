// The grid builder's first filter: one triangle against every voxel of a block (its candidate
// voxels), by the separating-axis test (Akenine-Möller 2001's 13 axes) with a forward error bound
// per axis (Higham 2002 §3.1's gamma_n, doubled). Every term that depends on one axis's voxel
// index is computed once per index, and the nine edge axes run as three 4-wide operations, so a
// voxel costs a few dozen additions and comparisons. It answers yes or no only where the exact
// predicate gives the same answer; unsure otherwise (the builder then asks
// triangle_box_filter.h's per-sign filter, and then CGAL).
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "triangle_box_filter.h"

namespace rtbench {

// A block of voxels: voxel i along axis a spans [lo[a][i], hi[a][i]]; size[a] voxels per axis.
struct VoxelBlock {
    std::array<const double*, 3> lo{}, hi{};
    glm::ivec3 size{0};
};

class VoxelBlockFilter {
public:
    // Tables for this triangle (vertices in double: exact copies of its floats) over this block.
    // Reuses its storage: one filter serves many triangles in turn.
    void reset(const std::array<glm::dvec3, 3>& vertices, const VoxelBlock& block);
    // Certainly not degenerate (not a segment or a point) by the filter's own arithmetic. Where
    // false, ask CGAL whether it is.
    bool proper() const { return proper_; }
    // Voxel (i, j, k) of the block against the closed triangle, which must not be degenerate
    // (proper(), or CGAL's word): the 13 axes decide only for a proper triangle, and the bounds
    // hold for its exact normal whatever proper() said.
    Overlap at(int i, int j, int k) const;

    // Four doubles, one per edge of the triangle (lane 3 unused, kept 0: a neutral axis), as
    // GCC's vector extension: each operation on them is one 4-wide operation.
    typedef double Lanes __attribute__((vector_size(32), aligned(16)));
    typedef std::int64_t LaneMask __attribute__((vector_size(32), aligned(16)));

private:
    // An axis's edge axes: per edge e, of the edge axis (edge e x box axis `drop`, written f(c) =
    // ep (c_q - s_q) - eq (c_p - s_p) in the plane of the other two box axes p, q, s the edge's
    // start) whose q is this axis, ep and whether it is >= 0; of the one whose p is it, eq and
    // whether it is >= 0; and s along this axis.
    struct AxisEdges {
        Lanes qScale, pScale, start;
        LaneMask qPositive, pPositive;
    };
    // What one voxel index of one axis contributes.
    struct IndexTerms {
        // Per edge: f's q term at its axis's min and max corner, its p term there, and their error shares.
        Lanes qMin, qMax, qMinError, qMaxError;
        Lanes pMin, pMax, pMinError, pMaxError;
        double planeMin, planeMax;  // normal[a] (face - v0[a]) at the faces giving the smaller, larger product
        double planeErrorMin, planeErrorMax, planeErrorAll;  // the terms' magnitudes there, and the larger
        unsigned overlaps;  // the triangle's extent meets this slab (exact)
        unsigned inside;    // bit v: vertex v lies within this slab (exact)
    };
    // The triangle's interval on the edge axes of one dropped box axis (lane e: edge e), [min(0,
    // f(w)), max(0, f(w))] for w the third vertex, widened or narrowed by f(w)'s error bound:
    // where it surely ends (above, below) and where it may end.
    struct EdgeIntervals {
        Lanes surelyAbove, surelyBelow;  // f above the first or below the second: beyond the triangle
        Lanes reachesUp, reachesDown;     // f at most the first and at least the second: within it
    };
    void setPlane(const std::array<glm::dvec3, 3>& v);
    void setEdges(const std::array<glm::dvec3, 3>& v);
    void fillIndexTerms(const std::array<glm::dvec3, 3>& v, int a, double faceLo, double faceHi, IndexTerms& t) const;

    glm::dvec3 lo_{0.0}, hi_{0.0};             // the triangle's bounding box
    glm::dvec3 normal_{0.0}, magnitude_{0.0};  // (v1 - v0) x (v2 - v0) as rounded; |a b| + |c d| per component
    std::array<AxisEdges, 3> axisEdges_{};
    std::array<EdgeIntervals, 3> intervals_{};  // per dropped box axis
    std::array<std::vector<IndexTerms>, 3> terms_;
    bool proper_ = false;
};

}  // namespace rtbench
