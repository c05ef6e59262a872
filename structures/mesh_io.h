// Mesh files through CGAL's polygon-soup reader (OFF, OBJ, PLY, STL), validated so that a bad
// file is a clear rtbench::Error naming it (and the line where one is known), never a crash or a
// silent partial load. Polygons are fan-triangulated (exact for convex polygons).
#pragma once
#include <string>

#include "mesh.h"

namespace rtbench {

// Reads a mesh file. Throws rtbench::Error on: a missing or unreadable file, an unknown
// extension, a reader failure, fewer elements than the header declares (OFF, PLY), a polygon
// with fewer than 3 vertices, an index out of range, a NaN or infinite coordinate, no triangles.
TriangleMesh readMeshFile(const std::string& path);

// Resolves `cgal:NAME` to Debian libcgal-demo's data/meshes/NAME.off, extracting the package's
// data.tar.gz once into the cache folder (RTBENCH_CACHE, else $XDG_CACHE_HOME/rtbench, else
// ~/.cache/rtbench). Returns the path of the extracted file.
std::string resolveCgalMesh(const std::string& name);

}  // namespace rtbench
