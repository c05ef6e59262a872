#include "mesh.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

namespace rtbench {

Bounds3 TriangleMesh::bounds() const {
    Bounds3 b;
    for (const glm::uvec3& t : triangles)
        for (int k = 0; k < 3; ++k) b.extend(vertices[t[k]]);
    return b;
}

std::size_t TriangleMesh::degenerateCount() const {
    using Point = CGAL::Exact_predicates_inexact_constructions_kernel::Point_3;
    auto point = [&](unsigned i) { return Point(vertices[i].x, vertices[i].y, vertices[i].z); };
    std::size_t count = 0;
    for (const glm::uvec3& t : triangles)  // exact predicate: zero area iff collinear
        if (CGAL::collinear(point(t[0]), point(t[1]), point(t[2]))) ++count;
    return count;
}

}  // namespace rtbench
