// An indexed triangle mesh: what every scene becomes before a structure is built over it.
#pragma once
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace rtbench {

struct Bounds3 {
    glm::vec3 min{std::numeric_limits<float>::max()};
    glm::vec3 max{-std::numeric_limits<float>::max()};
    void extend(glm::vec3 p) {
        min = glm::min(min, p);
        max = glm::max(max, p);
    }
    glm::vec3 extent() const { return max - min; }
    bool empty() const { return min.x > max.x; }
};

struct TriangleMesh {
    std::string name;                   // file path, cgal:NAME or procedural:NAME
    std::vector<glm::vec3> vertices;
    std::vector<glm::uvec3> triangles;  // indices into vertices
    std::size_t polygonsRead = 0;       // polygons before triangulation
    std::size_t elementsSkipped = 0;    // file elements that are not surfaces (OBJ 'l', 'p')
    std::string elementsSkippedWhat;    // what they were, e.g. "2 line elements ('l')"; "" if none

    Bounds3 bounds() const;
    // Zero-area triangles (repeated vertices or collinear): kept, counted, never hit by any method.
    std::size_t degenerateCount() const;
};

}  // namespace rtbench
