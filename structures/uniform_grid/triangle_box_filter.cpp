#include "triangle_box_filter.h"

#include <algorithm>
#include <cmath>

namespace rtbench {

namespace {

// A sign the filter is sure of, or not. The inputs are doubles (a float vertex, a voxel bound);
// each factor below is one rounded difference of two of them (-ffp-contract=off: no fused
// multiply-add), as Shewchuk's bounds assume. A computed difference is 0 only when its two
// inputs are equal, so a product with a zero factor is exactly 0.
enum Sign { Negative = -1, Zero = 0, Positive = 1, Unknown = 2 };

constexpr double kEpsilon = 0x1p-53;                              // Shewchuk's epsilon: half an ulp of 1
constexpr double kOrient2dBound = (3.0 + 16.0 * kEpsilon) * kEpsilon;  // ccwerrboundA
constexpr double kOrient3dBound = (7.0 + 56.0 * kEpsilon) * kEpsilon;  // o3derrboundA

Sign certain(double det, double errorBound) {
    if (det > errorBound) return Positive;
    if (-det > errorBound) return Negative;
    return Unknown;
}

// sign(a * b - c * d), each factor a rounded difference of inputs.
Sign sign2(double a, double b, double c, double d) {
    if ((a == 0.0 || b == 0.0) && (c == 0.0 || d == 0.0)) return Zero;
    const double left = a * b, right = c * d;
    return certain(left - right, kOrient2dBound * (std::abs(left) + std::abs(right)));
}

// sign of orient3d(p0, p1, p2, q) (Shewchuk's orient3d, first stage): which side of the plane
// through p0, p1, p2 the point q lies on.
Sign orient3d(const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& p2, const glm::dvec3& q) {
    const glm::dvec3 a = p0 - q, b = p1 - q, c = p2 - q;
    auto zeroTerm = [](double z, double x1, double y1, double x2, double y2) {
        return z == 0.0 || ((x1 == 0.0 || y1 == 0.0) && (x2 == 0.0 || y2 == 0.0));
    };
    if (zeroTerm(a.z, b.x, c.y, c.x, b.y) && zeroTerm(b.z, c.x, a.y, a.x, c.y) && zeroTerm(c.z, a.x, b.y, b.x, a.y))
        return Zero;
    const double bxcy = b.x * c.y, cxby = c.x * b.y, cxay = c.x * a.y, axcy = a.x * c.y, axby = a.x * b.y, bxay = b.x * a.y;
    const double det = a.z * (bxcy - cxby) + b.z * (cxay - axcy) + c.z * (axby - bxay);
    const double permanent = (std::abs(bxcy) + std::abs(cxby)) * std::abs(a.z) +
                             (std::abs(cxay) + std::abs(axcy)) * std::abs(b.z) +
                             (std::abs(axby) + std::abs(bxay)) * std::abs(c.z);
    return certain(det, kOrient3dBound * permanent);
}

// What the signs of one axis's tests say: the axis separates (every sign certain, all strictly
// on one side), cannot separate (a certain sign on each side, or on it), or perhaps.
enum class Axis { Separates, Overlaps, Unsure };

struct SideTally {
    bool allPositive = true, allNegative = true;  // every certain sign so far strictly so
    bool unknown = false;
    void add(Sign s) {
        if (s == Unknown) {
            unknown = true;
            return;
        }
        allPositive = allPositive && s == Positive;
        allNegative = allNegative && s == Negative;
    }
    Axis verdict() const {
        if (!allPositive && !allNegative) return Axis::Overlaps;
        return unknown ? Axis::Unsure : Axis::Separates;
    }
};

// The triangle's plane: separates when every box corner lies strictly on one side.
Axis planeAxis(const FilterTriangle& t, const glm::dvec3& lo, const glm::dvec3& hi) {
    SideTally tally;
    for (int k = 0; k < 8; ++k) {
        const glm::dvec3 corner(k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z);
        tally.add(orient3d(t.v[0], t.v[1], t.v[2], corner));
        if (tally.verdict() == Axis::Overlaps) return Axis::Overlaps;
    }
    return tally.verdict();
}

// The axis edge x (box axis `drop`), seen in the plane of the other two axes (p, q): with
// f(x) = cross(edge, x - start), the triangle spans [min(0, f(w)), max(0, f(w))] (w its third
// vertex), and the axis separates when every corner c of the box's rectangle has f(c) beyond
// both ends on one side: sign(f(c)) and sign(f(c) - f(w)) = sign(cross(edge, c - w)) all
// positive, or all negative. An edge along the box axis gives no axis (edge x axis = 0).
Axis edgeAxis(const glm::dvec3& start, const glm::dvec3& end, const glm::dvec3& w, int drop, const glm::dvec3& lo,
              const glm::dvec3& hi) {
    const int p = (drop + 1) % 3, q = (drop + 2) % 3;
    const double ep = end[p] - start[p], eq = end[q] - start[q];
    if (ep == 0.0 && eq == 0.0) return Axis::Overlaps;
    SideTally tally;
    for (int k = 0; k < 4; ++k) {
        const double cp = k & 1 ? hi[p] : lo[p], cq = k & 2 ? hi[q] : lo[q];
        tally.add(sign2(ep, cq - start[q], eq, cp - start[p]));
        tally.add(sign2(ep, cq - w[q], eq, cp - w[p]));
        if (tally.verdict() == Axis::Overlaps) return Axis::Overlaps;
    }
    return tally.verdict();
}

bool inside(const glm::dvec3& v, const glm::dvec3& lo, const glm::dvec3& hi) {
    return v.x >= lo.x && v.x <= hi.x && v.y >= lo.y && v.y <= hi.y && v.z >= lo.z && v.z <= hi.z;
}

}  // namespace

FilterTriangle::FilterTriangle(const std::array<glm::dvec3, 3>& vertices)
    : v(vertices), lo(glm::min(glm::min(v[0], v[1]), v[2])), hi(glm::max(glm::max(v[0], v[1]), v[2])) {}

Overlap filteredTriangleBoxOverlap(const FilterTriangle& t, const glm::dvec3& lo, const glm::dvec3& hi) {
    // The box's three face normals: the bounding boxes (comparisons, exact).
    for (int a = 0; a < 3; ++a)
        if (t.hi[a] < lo[a] || t.lo[a] > hi[a]) return Overlap::No;
    for (const glm::dvec3& v : t.v)
        if (inside(v, lo, hi)) return Overlap::Yes;
    bool unsure = false;
    auto judge = [&](Axis axis) {
        unsure = unsure || axis == Axis::Unsure;
        return axis == Axis::Separates;
    };
    if (judge(planeAxis(t, lo, hi))) return Overlap::No;
    for (int e = 0; e < 3; ++e)
        for (int drop = 0; drop < 3; ++drop)
            if (judge(edgeAxis(t.v[e], t.v[(e + 1) % 3], t.v[(e + 2) % 3], drop, lo, hi))) return Overlap::No;
    return unsure ? Overlap::Unsure : Overlap::Yes;
}

}  // namespace rtbench
