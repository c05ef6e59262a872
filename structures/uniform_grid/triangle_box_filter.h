// A floating-point filter in front of CGAL's exact triangle-box test: the separating-axis test
// (Akenine-Möller 2001's 13 axes) with every sign it needs certified by Shewchuk's static error
// bounds (1997, orient2d and orient3d's first stage), so it answers yes or no only where the
// exact predicate would give the same answer, and "unsure" otherwise (the builder then asks
// CGAL). The grid's cells are therefore the exact ones, bit for bit.
#pragma once
#include <array>

#include <glm/glm.hpp>

namespace rtbench {

enum class Overlap { No, Yes, Unsure };

// A triangle's vertices in double (exact copies of its floats), with what every box test reuses.
struct FilterTriangle {
    std::array<glm::dvec3, 3> v;
    glm::dvec3 lo, hi;  // its bounding box
    explicit FilterTriangle(const std::array<glm::dvec3, 3>& vertices);
};

// Whether the closed triangle (not degenerate: the builder sends those to CGAL) meets the closed
// box [lo, hi]; Unsure where rounding could change a sign the answer depends on.
Overlap filteredTriangleBoxOverlap(const FilterTriangle& triangle, const glm::dvec3& lo, const glm::dvec3& hi);

}  // namespace rtbench
