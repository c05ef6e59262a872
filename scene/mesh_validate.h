// Validation of mesh files before any reader sees them: every declared count against the file
// size, every index, every coordinate, every byte accounted for. A bad file is an rtbench::Error
// naming it and the line (text) or byte offset (binary) of the first problem.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/text.h"
#include <string_view>
#include <vector>

namespace rtbench {

enum class MeshFormat { Off, Obj, PlyAscii, PlyBinary, StlAscii, StlBinary };

// What validation found, and for text formats the bytes to hand to CGAL's reader instead of
// the file's: a normalized copy of the same mesh (vertex coordinates and face indices only, one
// element a line; OFF with all three header counts, OBJ with absolute indices and without the
// elements rtbench skips, ASCII STL as one solid). PLY and binary STL go to CGAL as they are.
struct ValidatedMesh {
    MeshFormat format = MeshFormat::Off;
    std::string normalized;    // empty: the file's own bytes
    std::size_t vertices = 0;  // 0 for STL (CGAL merges equal points)
    std::size_t faces = 0;
    std::vector<std::uint64_t> faceAt;  // per face: its line (text) or byte offset (binary)
    std::size_t elementsSkipped = 0;
    std::string skippedWhat;  // e.g. "3 OBJ line elements ('l')"

    // "NAME:LINE" (text formats) or "NAME: byte N" (binary) for face f.
    std::string faceLocation(const std::string& name, std::size_t f) const;
};

// `name` is the file name used in messages; its extension (any case) selects the format.
ValidatedMesh validateMesh(std::string_view bytes, const std::string& name);

}  // namespace rtbench
