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
// facing inward, vertices shared: with 8 (768 triangles), its edges lie on the planes of an
// 8x8x8 grid over it, and the origin is a voxel corner.
TriangleMesh closedBox(int quadsPerEdge = 8);
// icosphere: the unit sphere as an icosahedron subdivided `levels` times (20 x 4^levels
// triangles; 4: 5,120), vertices shared, in float.
TriangleMesh icosphere(int levels = 4);
// tetrahedron: a regular-ish tetrahedron around the origin (4 triangles).
TriangleMesh tetrahedron();

// The NAMEs of procedural:NAME.
const std::vector<std::string>& proceduralSceneNames();
// "christen_a" | "christen_b" | "christen_b_thesis" | "closed_box" | "icosphere" | "tetrahedron";
// throws rtbench::Error listing the names otherwise.
TriangleMesh proceduralScene(const std::string& name);

// The scene's own viewpoint, where fitting to the bounds would not do: scene B is seen from
// inside its room (from outside, every ray would stop at a wall in its first voxel); the closed
// meshes from the origin inside them, looking along +z.
std::optional<PinholeCamera> proceduralCamera(const std::string& name, float verticalFovDegrees);

// Appends an axis-aligned box (12 triangles, outward-facing unless inward).
void appendBox(TriangleMesh& mesh, glm::vec3 lo, glm::vec3 hi, bool inward = false);

}  // namespace rtbench
