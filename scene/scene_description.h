// Scene descriptions: a TOML file (scene.source = "scenes/NAME.toml", relative to the config) that
// lists meshes, each placed once ([[object]]) or copied many times by a fixed-seed generator
// ([[scatter]]), and becomes one TriangleMesh named by the description's path.
//
//   name = "teapot in a stadium"   # optional title (documentation only)
//
//   [[object]]                     # one mesh placed once
//   mesh = "cgal:bunny00"          # a mesh file (.off/.obj/.ply/.stl, relative to THIS file),
//                                  # cgal:NAME or procedural:NAME; descriptions do not nest
//   anchor = "base"                # the mesh point that `translate` moves to: "origin" (the file's
//                                  # own origin; the default for objects), "center" (the centre of
//                                  # its box) or "base" (the centre of its box's bottom face)
//   size = 2.0                     # optional: first scale uniformly so that the largest extent of
//                                  # the mesh's box is 2.0 (meshes come in any units)
//   scale = 2.0                    # then this: one number, or [sx, sy, sz]; each > 0; default 1
//   rotate_deg = [0, 90, 0]        # then rotate about x, then y, then z (right-handed, degrees,
//                                  # about the anchor); default [0, 0, 0]
//   translate = [0, 0, 0]          # then move the anchor here; default [0, 0, 0]
//
//   [[scatter]]                    # `count` copies of one mesh
//   mesh = "cgal:sphere"
//   count = 500                    # 1 .. 16,777,216
//   seed = 7                       # 0 .. 2^32-1, std::mt19937's seed
//   box_min = [-10, 0, -10]        # each copy's anchor is drawn uniformly in [box_min, box_max]
//   box_max = [10, 5, 10]
//   anchor = "center"              # as for objects; the default for scatters is "center"
//   size = 1.0                     # as for objects
//   scale = [0.5, 2.0]             # a uniform scale drawn per copy in [min, max], or one number
//   random_rotation = true         # true: a uniformly random orientation (a random unit
//                                  # quaternion); "x", "y" or "z": a random turn about that axis
//                                  # only ("y" keeps objects upright); false (the default): none
//
//   [[material]]                   # what Whitted ray tracing (rays.type = whitted) sees of a mesh
//   mesh = "cgal:sphere"           # every copy of a mesh an [[object]] or [[scatter]] places
//                                  # (files by their resolved path); one material per mesh
//   type = "glass"                 # "diffuse", "mirror" or "glass"; and only its own keys:
//   colour = [0.8, 0.8, 0.8]       # diffuse and mirror: the diffuse colour, each in [0, 1]
//   reflectance = 0.8              # mirror: the fraction reflected, in (0, 1]; default 1
//   ior = 1.5                      # glass: index of refraction, in [0.01, 100]; default 1.5
//                                  # (meshes no [[material]] covers take the run's whitted.surface)
//
//   [[light]]                      # a point light (Whitted's shadow rays; none: the run's
//   position = [0, 5, 0]           # light.position); in the description's coordinates
//
// Vertex v of a placement becomes  translate + Rz Ry Rx (scale * sizeFactor * (v - anchor)),
// computed in double with IEEE basic operations only (sin and cos by a fixed polynomial, no libm;
// std::mt19937 with explicit arithmetic, no std::*_distribution; the build forbids FMA
// contraction) and rounded to float once: a description gives bit-identical vertices on every
// machine. A copy's draws, in order: its anchor's x, y, z; its scale (only for a range); its
// rotation (one draw for an axis; for true, 4 draws per attempt of a rejection sample of the
// unit 4-ball). Each draw is a double in [0, 1) from two mt19937 outputs (53 bits, as
// genrand_res53), and a value is lo + (hi - lo) * u. Copies may intersect each other.
//
// Errors (rtbench::Error) name the description and the line: TOML syntax, unknown keys, wrong
// types, non-finite numbers, non-positive scales or sizes, box_min > box_max, counts out of range,
// a material on a mesh nothing places or a key its type does not read, an empty list of
// materials or lights,
// more than kMaxDescriptionTriangles triangles in all, a mesh that cannot be read, a vertex
// placed beyond the range every method handles (scene_limits.h). Each mesh is read once per
// description however often it is placed.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "mesh.h"

namespace rtbench {

// Triangles (and vertices: 3x this) one description may produce in all: 2^24, about 16.8M.
constexpr std::size_t kMaxDescriptionTriangles = std::size_t(1) << 24;

// One placed copy of a mesh: where its triangles and vertices lie in the result.
struct PlacedCopy {
    std::string mesh;  // its source as written in the description
    std::size_t firstVertex = 0, vertexCount = 0;
    std::size_t firstTriangle = 0, triangleCount = 0;
    glm::dvec3 anchorAt{0.0};  // where its anchor went (translate, or the drawn position)
    glm::dvec3 scale{1.0};     // the scale applied after the size factor
};

struct SceneDescription {
    std::string title;  // the `name` key, "" if absent
    TriangleMesh mesh;  // every placement, in file order; name = the description path
    std::vector<PlacedCopy> copies;
    std::size_t meshesRead = 0;  // distinct meshes read (each once, however often placed)
};

// Reads and places a scene description (see above). Throws rtbench::Error.
SceneDescription readSceneDescription(const std::string& path);

// Any scene.source: procedural:NAME, cgal:NAME, a description (*.toml) or a mesh file; relative
// paths resolve against baseDir. The mesh's name is the source (cgal:, procedural:) or the
// resolved path (files, descriptions).
TriangleMesh loadSceneSource(const std::string& source, const std::string& baseDir);

// What can be known of a scene.source without reading it: a known procedural name, a cgal: name
// libcgal-demo has (suggesting the nearest when not), something at a file's path (what it is, a
// link or a FIFO, the run's reader says). Throws rtbench::Error.
// (A description's meshes are checked when it is read.)
void checkSceneSource(const std::string& source, const std::string& baseDir);

// sin and cos of an angle in degrees with IEEE basic operations only: exact at multiples of 90,
// within 1e-15 elsewhere, the same bits on every machine. (Exposed for tests.)
void sinCosDegrees(double degrees, double& sine, double& cosine);

}  // namespace rtbench
