// Simplified scenes, "no more than a scene needs": edge collapse (CGAL Surface_mesh_simplification,
// Lindstrom-Turk cost and placement, CGAL's defaults) down to a target triangle count.
#pragma once
#include <cstddef>

#include "mesh.h"

namespace rtbench {

struct SimplifiedMesh {
    TriangleMesh mesh;          // the simplified mesh; name = the source's name
    std::size_t collapses = 0;  // edges collapsed
    bool unchanged = false;     // the source mesh itself (target >= its count): the same triangles and ids
    double ms = 0.0;            // wall time of the whole call (conversion included)
};

// Collapses edges until the mesh has at most targetTriangles triangles. A collapse removes the
// two triangles of an edge inside the surface, one on a border. With exact = true the result has
// exactly targetTriangles triangles or it throws rtbench::Error saying why not (a closed surface
// keeps its parity; one triangle above the target, only a border edge is collapsed; a target
// above the mesh's count, which simplification cannot reach); with exact = false it stops at the
// first count <= target. A target equal to the mesh's count (with exact = false, any target at or
// above it) returns the mesh unchanged (0 collapses). Triangles with a repeated vertex index are
// dropped; zero-area ones are kept, and CGAL collapses the zero-length edges among them first,
// whatever the target.
// Besides CGAL's checks, a collapse is refused where it would leave a triangle of zero area with
// its vertices rounded to float (as the result holds them): simplification adds none, and
// mesh.degenerateCount() counts those of the source it kept.
// Throws rtbench::Error (naming mesh.name) on: target 0; an exact target above the count (the
// scene has only N triangles, fewer than asked for); an index out of range; a coordinate that
// is not finite; no triangle of three distinct indices; a soup CGAL cannot orient into a
// 2-manifold surface (orient_polygon_soup duplicates points where it must, so none seen yet); a
// simplifier that stops above the target (no edge can be collapsed without breaking the surface:
// at what count, and how many points orient_polygon_soup duplicated if it did); an exact count
// that cannot be reached (why; for a parity problem, the counts next to it that can).
SimplifiedMesh simplifyMesh(const TriangleMesh& mesh, std::size_t targetTriangles, bool exact);

}  // namespace rtbench
