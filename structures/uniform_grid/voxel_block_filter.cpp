#include "voxel_block_filter.h"

#include <algorithm>
#include <cmath>

namespace rtbench {

namespace {

using Lanes = VoxelBlockFilter::Lanes;
using LaneMask = VoxelBlockFilter::LaneMask;

// Forward error bounds, doubled: the slack covers the rounding of the thresholds and sums built
// from them. Each factor is a rounded difference of two inputs (a float vertex, a voxel face;
// -ffp-contract=off: no fused multiply-add), so its sign is exact and it is 0 only where the
// inputs are equal. Both are powers of 2: scaling by them is exact. The functions marked
// target_clones are built twice, for AVX2 (4 lanes at once) and the baseline (2 + 2): the same
// operations on the same values, so the same results.
constexpr double kEpsilon = 0x1p-53;             // half an ulp of 1
constexpr double kEdgeBound = 8.0 * kEpsilon;    // twice gamma_4: a b - c d of differences
constexpr double kPlaneBound = 16.0 * kEpsilon;  // twice gamma_8: a normal's components times differences

// A 4-wide argument is passed one way by the AVX2 clones and another by the baseline code
// (GCC's -Wpsabi note), so a helper taking one must never be called: it is always inlined.
#pragma GCC diagnostic ignored "-Wpsabi"
[[gnu::always_inline]] inline Lanes magnitude(Lanes x) { return x < 0.0 ? -x : x; }

}  // namespace

// The plane axis: normal = (v1 - v0) x (v2 - v0), each component a b - c d, and |a b| + |c d|.
[[gnu::always_inline]] inline void VoxelBlockFilter::setPlane(const std::array<glm::dvec3, 3>& v) {
    const glm::dvec3 e1 = v[1] - v[0], e2 = v[2] - v[0];
    proper_ = false;
    for (int a = 0; a < 3; ++a) {
        const double left = e1[(a + 1) % 3] * e2[(a + 2) % 3], right = e1[(a + 2) % 3] * e2[(a + 1) % 3];
        normal_[a] = left - right;
        magnitude_[a] = std::abs(left) + std::abs(right);
        proper_ = proper_ || std::abs(normal_[a]) > kEdgeBound * magnitude_[a];  // beyond gamma_4 twice: not 0
    }
}

// The nine edge axes: edge e (start s = v[e], end v[e + 1], third vertex w = v[e + 2]) x box axis
// d, p = d + 1 and q = d + 2 (mod 3), the three edges in lanes; f(w) = ep (w_q - s_q) - eq (w_p -
// s_p) with its error bound gives the triangle's interval.
[[gnu::always_inline]] inline void VoxelBlockFilter::setEdges(const std::array<glm::dvec3, 3>& v) {
    Lanes start[3], end[3], third[3];  // per box axis: the lanes' s, end and w along it
    for (int a = 0; a < 3; ++a) {
        start[a] = Lanes{v[0][a], v[1][a], v[2][a], 0.0};
        end[a] = Lanes{v[1][a], v[2][a], v[0][a], 0.0};
        third[a] = Lanes{v[2][a], v[0][a], v[1][a], 0.0};
    }
    for (int d = 0; d < 3; ++d) {
        const int p = (d + 1) % 3, q = (d + 2) % 3;
        const Lanes ep = end[p] - start[p], eq = end[q] - start[q];
        const Lanes termQ = ep * (third[q] - start[q]), termP = eq * (third[p] - start[p]);
        const Lanes f = termQ - termP, error = kEdgeBound * (magnitude(termQ) + magnitude(termP)), zero{};
        const Lanes up = f + error, down = f - error;
        intervals_[d] = {up > zero ? up : zero, down < zero ? down : zero, down > zero ? down : zero, up < zero ? up : zero};
        axisEdges_[q].qScale = ep, axisEdges_[q].qPositive = ep >= zero;
        axisEdges_[p].pScale = eq, axisEdges_[p].pPositive = eq >= zero;
    }
    for (int a = 0; a < 3; ++a) axisEdges_[a].start = start[a];
}

// What the voxel index with faces [faceLo, faceHi] along axis a contributes to every test.
[[gnu::always_inline]] inline void VoxelBlockFilter::fillIndexTerms(const std::array<glm::dvec3, 3>& v, int a, double faceLo, double faceHi, IndexTerms& t) const {
    t.overlaps = !(hi_[a] < faceLo || lo_[a] > faceHi);
    t.inside = 0;
    for (int k = 0; k < 3; ++k) t.inside |= unsigned(v[k][a] >= faceLo && v[k][a] <= faceHi) << k;
    // Plane: the face giving the smaller product makes the computed minimum over the voxel's
    // corners (rounding is monotone), and the other the maximum.
    const double dLo = faceLo - v[0][a], dHi = faceHi - v[0][a];
    const double pLo = normal_[a] * dLo, pHi = normal_[a] * dHi;
    const double mLo = magnitude_[a] * std::abs(dLo), mHi = magnitude_[a] * std::abs(dHi);
    const bool loIsMin = pLo <= pHi;
    t.planeMin = loIsMin ? pLo : pHi, t.planeMax = loIsMin ? pHi : pLo;
    t.planeErrorMin = loIsMin ? mLo : mHi, t.planeErrorMax = loIsMin ? mHi : mLo;
    t.planeErrorAll = std::max(mLo, mHi);
    // Edges: the signs of ep and eq are exact, so they pick the exact extreme corners.
    const AxisEdges& x = axisEdges_[a];
    const Lanes lo = Lanes{} + faceLo, hi = Lanes{} + faceHi;
    t.qMin = x.qScale * ((x.qPositive ? lo : hi) - x.start), t.qMax = x.qScale * ((x.qPositive ? hi : lo) - x.start);
    t.pMin = x.pScale * ((x.pPositive ? hi : lo) - x.start), t.pMax = x.pScale * ((x.pPositive ? lo : hi) - x.start);
    t.qMinError = kEdgeBound * magnitude(t.qMin), t.qMaxError = kEdgeBound * magnitude(t.qMax);
    t.pMinError = kEdgeBound * magnitude(t.pMin), t.pMaxError = kEdgeBound * magnitude(t.pMax);
}

__attribute__((target_clones("avx2", "default"))) void VoxelBlockFilter::reset(const std::array<glm::dvec3, 3>& v, const VoxelBlock& block) {
    lo_ = glm::min(glm::min(v[0], v[1]), v[2]), hi_ = glm::max(glm::max(v[0], v[1]), v[2]);
    setPlane(v);
    setEdges(v);
    for (int a = 0; a < 3; ++a) {
        terms_[a].resize(block.size[a]);
        for (int i = 0; i < block.size[a]; ++i) fillIndexTerms(v, a, block.lo[a][i], block.hi[a][i], terms_[a][i]);
    }
}

__attribute__((target_clones("avx2", "default"))) Overlap VoxelBlockFilter::at(int i, int j, int k) const {
    const std::array<const IndexTerms*, 3> t{&terms_[0][i], &terms_[1][j], &terms_[2][k]};
    // The box's three face normals (the bounding boxes), and a vertex inside: exact.
    if (!(t[0]->overlaps & t[1]->overlaps & t[2]->overlaps)) return Overlap::No;
    if (t[0]->inside & t[1]->inside & t[2]->inside) return Overlap::Yes;
    // The plane: separates when every corner is strictly on one side; certainly does not when
    // the corners giving the computed extremes are certainly on both sides (or on it).
    const double fMin = (t[0]->planeMin + t[1]->planeMin) + t[2]->planeMin;
    const double fMax = (t[0]->planeMax + t[1]->planeMax) + t[2]->planeMax;
    const double errorAll = kPlaneBound * ((t[0]->planeErrorAll + t[1]->planeErrorAll) + t[2]->planeErrorAll);
    const double errorMin = kPlaneBound * ((t[0]->planeErrorMin + t[1]->planeErrorMin) + t[2]->planeErrorMin);
    const double errorMax = kPlaneBound * ((t[0]->planeErrorMax + t[1]->planeErrorMax) + t[2]->planeErrorMax);
    if (fMin > errorAll || fMax < -errorAll) return Overlap::No;
    bool unsure = !(fMin <= -errorMin && fMax >= errorMax);
    // The nine edge axes, three at a time: f over the voxel's rectangle in (p, q), each end off by
    // at most half its error, against the triangle's interval.
    LaneMask separates{0, 0, 0, 0}, spans{-1, -1, -1, -1};
    for (int d = 0; d < 3; ++d) {
        const IndexTerms &p = *t[(d + 1) % 3], &q = *t[(d + 2) % 3];
        const EdgeIntervals& h = intervals_[d];
        const Lanes fLow = q.qMin - p.pMin, fHigh = q.qMax - p.pMax;
        const Lanes errorLow = q.qMinError + p.pMinError, errorHigh = q.qMaxError + p.pMaxError;
        separates |= (fLow - errorLow > h.surelyAbove) | (fHigh + errorHigh < h.surelyBelow);
        spans &= (fLow + errorLow <= h.reachesUp) & (fHigh - errorHigh >= h.reachesDown);
    }
    if (separates[0] | separates[1] | separates[2]) return Overlap::No;  // lane 3 never separates
    return unsure || !(spans[0] & spans[1] & spans[2]) ? Overlap::Unsure : Overlap::Yes;
}

}  // namespace rtbench
