// Procedural test scenes: Christen 2005 (§6.1), generated with fixed seeds, and closed meshes.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <optional>

#include "camera.h"
#include "mesh.h"

namespace rtbench {

// Scene A: three axis-aligned boxes of different sizes on a floor-less stage (36 triangles).
TriangleMesh christenSceneA();

// Scene B: a room (6 inward walls, 12 triangles) with 166 small cubes distributed in it by a
// fixed-seed generator: 2,004 triangles, many empty voxels and many distinct occluders.
// Christen's Table 6.1 gives 2,064 (see procedural.cpp for what differs).
TriangleMesh christenSceneB(std::uint32_t seed = 2005);

// Scene B with Table 6.1's 2,064 triangles: the same room and generator, 171 cubes instead of 166
// (the first 166 are christen_b's cubes, bit for bit). procedural:christen_b_thesis.
TriangleMesh christenSceneBThesis(std::uint32_t seed = 2005);

// Closed meshes for accuracy and stability (every ray from inside must hit; a miss is a leak):
// closed_box: the cube [-1, 1]^3, each face split into `quadsPerEdge`^2 squares of two triangles,
// facing outward (right-hand normals), vertices shared: with 8 (768 triangles), its edges lie on the planes of an
// 8x8x8 grid over it, and the origin is a voxel corner.
TriangleMesh closedBox(int quadsPerEdge = 8);
// icosphere: the unit sphere as an icosahedron subdivided `levels` times (20 x 4^levels
// triangles; 4: 5,120), vertices shared, in float.
TriangleMesh icosphere(int levels = 4);
// tetrahedron: a regular-ish tetrahedron around the origin (4 triangles).
TriangleMesh tetrahedron();

// Purcell et al. 2002's other scenes of Table 2, invented to their description (§4.1): the paper
// gives their sizes, their grids and a sentence each, nothing of their geometry.
// forest: "trees with millions of tiny triangles", "moderate depth complexity" (his: 1.0M
// triangles, grid 581 x 128 x 581). A 20 x 20 ground square (2 triangles) and kForestTrees trees,
// each a trunk (a box, 12) and a crown of kForestLeavesPerTree one-triangle leaves (each within
// half a percent of the tree's height of its centre) in an ellipsoid;
// heights 3 to 4.4, so the box is about 20 x 4.4 x 20, his proportions: 1,000,002 triangles.
constexpr int kForestTrees = 250, kForestLeavesPerTree = 3988;
TriangleMesh forest(std::uint32_t seed = 2002);
// building: "walls made of large polygons, furnishings made of small polygons", "high depth
// complexity" (his Soda Hall: 1.5M triangles, grid 250 x 198 x 128; ours 1,373,652). Ten storeys of 4 x 2 rooms,
// 39.45 x 31.25 x 20.2 with its walls (his proportions); floors and walls are boxes, each outer wall of a room has a
// window, each inner wall a door; each room a table (5 boxes) and four chairs (6 boxes each), every
// furniture box's faces split into 7 x 7 squares (588 triangles).
TriangleMesh building();
// Appends the box [lo, hi] with each face split into quadsPerEdge^2 squares (outward-facing).
void appendMeshedBox(TriangleMesh& mesh, glm::vec3 lo, glm::vec3 hi, int quadsPerEdge);

// The NAMEs of procedural:NAME.
const std::vector<std::string>& proceduralSceneNames();
// "christen_a" | "christen_b" | "christen_b_thesis" | "closed_box" | "icosphere" | "tetrahedron" |
// "forest" | "building";
// throws rtbench::Error listing the names otherwise.
TriangleMesh proceduralScene(const std::string& name);

// The scene's own viewpoint, where fitting to the bounds would not do: scene B is seen from
// inside its room (from outside, every ray would stop at a wall in its first voxel); the closed
// meshes from the origin inside them, looking along +z.
std::optional<PinholeCamera> proceduralCamera(const std::string& name, float verticalFovDegrees);

// Appends an axis-aligned box (12 triangles, outward-facing unless inward).
void appendBox(TriangleMesh& mesh, glm::vec3 lo, glm::vec3 hi, bool inward = false);

}  // namespace rtbench
