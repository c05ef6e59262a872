// The triangles' vertices as every structure keeps them on the device, in mesh order: float
// (gpu::Triangle, 48 bytes a triangle) or, for a scene snapped to a vertex lattice
// (intersection.vertex_bits), packed to 16-bit lattice coordinates (gpu::kPackedTriangleWords,
// 20 bytes): reduced precision where it buys bandwidth, Purcell's bottleneck (Purcell et al. 2002
// §5.2). One lattice over the scene's box, so a vertex shared by triangles stays shared and a
// closed mesh stays closed; the kernels decode a vertex as origin + q * step (kernels/traversal_common.glsl).
#pragma once
#include <cstdint>
#include <vector>

#include "kernels/gpu_layout.h"
#include "structures/structure.h"
#include "scene/mesh.h"

namespace rtbench {

// The lattice of `bits` bits per axis over a box: origin = its min corner (a coordinate below the
// smallest normal float in magnitude becomes 0: a device may flush subnormals), step = the least
// power of two with (2^bits - 1) * step >= the largest extent from the origin. Throws
// rtbench::Error when bits is outside 1..16 or the step would not be a normal float.
VertexLattice vertexLattice(const Bounds3& box, unsigned bits);

// A lattice point as the kernels compute it: origin + float(q) * step, the product exact.
glm::vec3 latticePoint(const VertexLattice& lattice, glm::uvec3 q);

// The mesh with every vertex of its triangles moved to the nearest lattice point (per axis, ties
// away from zero; a vertex no triangle uses stays), lattice set. Distinct vertices may merge, and
// triangles may become degenerate.
TriangleMesh snapToLattice(const TriangleMesh& mesh, unsigned bits);

// The mesh's triangles as float vertices (gpu::Triangle, w = 0), in mesh order.
std::vector<gpu::Triangle> floatTriangles(const TriangleMesh& mesh);

// Bytes the device stores (and a kernel reads) per triangle's vertices.
std::uint64_t triangleVertexBytes(const VertexLattice& lattice);

// The vertex buffer of a structure: float triangles, or their lattice coordinates packed.
class TriangleStore {
public:
    // `triangles` in mesh order (kept by the structure, which builds over them); packs them when
    // lattice.bits != 0, checking that every vertex is a lattice point (else rtbench::Error).
    TriangleStore(const std::vector<gpu::Triangle>& triangles, const VertexLattice& lattice);
    // It points into its structure's triangles: neither copied nor moved with them.
    TriangleStore(const TriangleStore&) = delete;
    TriangleStore& operator=(const TriangleStore&) = delete;

    StructureBuffer buffer() const;         // what the device binds
    std::uint64_t bytes() const;            // its size
    const VertexLattice& lattice() const { return lattice_; }

    // Points the shared source's buffers at this store (CPU reference).
    template <class Kernels>
    void bind(Kernels& k) const {
        k.triangles = triangles_->data();
        k.packedTriangles = packed_.data();
    }

private:
    const std::vector<gpu::Triangle>* triangles_;
    std::vector<std::uint32_t> packed_;
    VertexLattice lattice_;
};

}  // namespace rtbench
