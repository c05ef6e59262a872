// Mesh files through CGAL's readers (OFF, OBJ, PLY, STL), validated before CGAL sees them
// (mesh_validate.h) so that a bad file is a clear rtbench::Error naming it and the line or byte
// where the problem is, never a crash, a huge allocation, output on stdout/stderr or a silent
// partial load. Polygons are triangulated by polygon_triangulation.h.
#pragma once
#include <string>
#include <string_view>

#include "mesh.h"

namespace rtbench {

// Reads a mesh file. Throws rtbench::Error on: a missing or unreadable file, an unknown
// extension, a declared count the file cannot hold, fewer or more elements than declared, a
// polygon with fewer than 3 vertices, a non-integer or out-of-range index, a NaN, infinite or
// beyond-single-precision coordinate, no faces (point clouds), a polygon that cannot be
// triangulated, anything the format does not allow.
TriangleMesh readMeshFile(const std::string& path);

// The same on a file's bytes; the extension of `nameWithExtension` selects the format, and the
// name is used in messages (an entry point for fuzzing).
TriangleMesh readMeshBytes(std::string_view bytes, const std::string& nameWithExtension);

// Resolves `cgal:NAME` to Debian libcgal-demo's data/meshes/NAME.off, extracting the package's
// data.tar.gz once (with libarchive) into the cache folder (RTBENCH_CACHE, else
// $XDG_CACHE_HOME/rtbench, else ~/.cache/rtbench) with a manifest of each file's hash; a cache
// without its manifest (emptied, interrupted) is extracted again. Returns the extracted file.
std::string resolveCgalMesh(const std::string& name);

// The NAMEs of cgal:NAME: libcgal-demo's data/meshes/*.off, sorted.
std::vector<std::string> cgalMeshNames();
// Levenshtein distance: the fewest single-character insertions, deletions and substitutions.
std::size_t editDistance(const std::string& a, const std::string& b);
// The `count` names of `names` nearest to `name`: those containing it (case ignored) first, then by
// edit distance (for "no such mesh" messages).
std::vector<std::string> nearestNames(const std::string& name, const std::vector<std::string>& names, std::size_t count);

// Reads `cgal:NAME`; throws rtbench::Error when the cached file differs from what was extracted.
TriangleMesh readCgalMesh(const std::string& name);

}  // namespace rtbench
