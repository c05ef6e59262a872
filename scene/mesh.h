// An indexed triangle mesh: what every scene becomes before a structure is built over it.
#pragma once
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "appearance.h"
#include "core/input_file.h"

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

// A lattice the vertices lie on (intersection.vertex_bits, structures/triangle_store.h): each vertex is
// origin + q * step in float, q an integer vector in [0, 2^bits), step a power of two.
struct VertexLattice {
    unsigned bits = 0;  // 0: float vertices, on no lattice
    glm::vec3 origin{0.0f};
    float step = 0.0f;
};

struct TriangleMesh {
    std::string name;                   // file path, cgal:NAME or procedural:NAME
    std::vector<glm::vec3> vertices;
    std::vector<glm::uvec3> triangles;  // indices into vertices
    std::size_t polygonsRead = 0;       // polygons before triangulation
    std::size_t elementsSkipped = 0;    // file elements that are not surfaces (OBJ 'l', 'p')
    std::string elementsSkippedWhat;    // what they were, e.g. "2 line elements ('l')"; "" if none
    VertexLattice lattice;              // bits != 0: every vertex lies on it, and structures store them packed
    std::vector<InputFile> inputs;      // the files read to make it, in reading order (none: procedural)
    Appearance appearance;              // materials and lights a scene description gives (else none)

    Bounds3 bounds() const;
    // Zero-area triangles (repeated vertices or collinear): kept, counted, never hit by any method.
    std::size_t degenerateCount() const;
};

}  // namespace rtbench
