// Triangulation of one mesh polygon (a face of an OFF/OBJ/PLY file) into triangles.
#pragma once
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace rtbench {

// Relative planarity tolerance for concave polygons: one with a vertex farther than this
// fraction of its bounding-box diagonal from its mean plane (Newell's normal through the
// centroid) is refused as non-planar.
inline constexpr double kPolygonPlanarityTolerance = 1e-2;

// Appends the triangles of the polygon `indices` (into `vertices`) to `out`, wound like the
// polygon. Every polygon is projected exactly onto the plane of its Newell normal's dominant
// axis. Triangles and polygons convex in that projection are fanned from their first vertex,
// as rtbench always did (a warped convex quad too). A concave polygon must be planar within
// kPolygonPlanarityTolerance; it is triangulated by a constrained Delaunay triangulation of its
// edges in the projection, keeping the faces inside it; edges walked twice (the bridge of a
// keyhole polygon, joining an outline to a hole) do not bound it. Collinear polygons (zero area)
// are fanned into degenerate triangles, which the mesh counts. Returns "" on success, else why
// the polygon cannot be triangulated (crossing edges, overlapping itself, zero net area with
// a non-collinear vertex, non-planar and concave), appending nothing.
std::string triangulatePolygon(const std::vector<glm::vec3>& vertices,
                               const std::vector<std::size_t>& indices,
                               std::vector<glm::uvec3>& out);

}  // namespace rtbench
