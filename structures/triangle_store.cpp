#include "triangle_store.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "core/error.h"

namespace rtbench {

VertexLattice vertexLattice(const Bounds3& box, unsigned bits) {
    if (bits < 1 || bits > 16) throw Error("vertex lattice: " + std::to_string(bits) + " bits per axis, expected 1 to 16");
    VertexLattice lattice;
    lattice.bits = bits;
    for (int axis = 0; axis < 3; ++axis)
        lattice.origin[axis] = std::abs(box.min[axis]) < std::numeric_limits<float>::min() ? 0.0f : box.min[axis];
    const glm::dvec3 extent = glm::dvec3(box.max) - glm::dvec3(lattice.origin);
    const double largest = std::max({extent.x, extent.y, extent.z});
    const double steps = double((1u << bits) - 1u);
    // The least power of two covering the box in 2^bits - 1 steps (any for a point).
    int exponent = -126;
    if (largest > 0.0) {
        exponent = std::ilogb(largest / steps);
        if (std::ldexp(1.0, exponent) * steps < largest) ++exponent;
    }
    if (exponent < -126 || exponent > 127)
        throw Error("vertex lattice: a step of 2^" + std::to_string(exponent) + " is not a normal float (the box spans " +
                    std::to_string(largest) + ")");
    lattice.step = std::ldexp(1.0f, exponent);
    return lattice;
}

glm::vec3 latticePoint(const VertexLattice& lattice, glm::uvec3 q) {
    return lattice.origin + glm::vec3(q) * lattice.step;  // the build forbids FMA contraction
}

namespace {

// The lattice coordinates of a vertex: nearest per axis, clamped to the lattice.
glm::uvec3 nearestLatticeCoordinates(const VertexLattice& lattice, glm::vec3 v) {
    const double top = double((1u << lattice.bits) - 1u);
    glm::uvec3 q;
    for (int axis = 0; axis < 3; ++axis) {
        const double steps = (double(v[axis]) - double(lattice.origin[axis])) / double(lattice.step);
        q[axis] = unsigned(std::clamp(std::round(steps), 0.0, top));
    }
    return q;
}

}  // namespace

TriangleMesh snapToLattice(const TriangleMesh& mesh, unsigned bits) {
    TriangleMesh snapped = mesh;
    snapped.lattice = vertexLattice(mesh.bounds(), bits);
    std::vector<bool> used(mesh.vertices.size(), false);
    for (const glm::uvec3& t : mesh.triangles) used[t.x] = used[t.y] = used[t.z] = true;
    for (std::size_t i = 0; i < snapped.vertices.size(); ++i)
        if (used[i]) snapped.vertices[i] = latticePoint(snapped.lattice, nearestLatticeCoordinates(snapped.lattice, snapped.vertices[i]));
    return snapped;
}

std::vector<gpu::Triangle> floatTriangles(const TriangleMesh& mesh) {
    std::vector<gpu::Triangle> triangles;
    triangles.reserve(mesh.triangles.size());
    for (const glm::uvec3& t : mesh.triangles)
        triangles.push_back({glm::vec4(mesh.vertices[t.x], 0.0f), glm::vec4(mesh.vertices[t.y], 0.0f),
                             glm::vec4(mesh.vertices[t.z], 0.0f)});
    return triangles;
}

std::uint64_t triangleVertexBytes(const VertexLattice& lattice) {
    return lattice.bits ? gpu::kPackedTriangleWords * 4 : sizeof(gpu::Triangle);
}

TriangleStore::TriangleStore(const std::vector<gpu::Triangle>& triangles, const VertexLattice& lattice)
    : triangles_(&triangles), lattice_(lattice) {
    if (!lattice.bits) return;
    packed_.reserve(triangles.size() * gpu::kPackedTriangleWords);
    for (std::size_t i = 0; i < triangles.size(); ++i) {
        std::uint32_t q[9];
        const glm::vec4* corners[3] = {&triangles[i].v0, &triangles[i].v1, &triangles[i].v2};
        for (int c = 0; c < 3; ++c) {
            const glm::vec3 v(*corners[c]);
            const glm::uvec3 coordinates = nearestLatticeCoordinates(lattice, v);
            const glm::vec3 decoded = latticePoint(lattice, coordinates);
            if (std::memcmp(&decoded, &v, sizeof v) != 0)
                throw Error("packed vertices: a vertex of triangle " + std::to_string(i) +
                            " is not a point of the scene's lattice (the scene must be snapped first)");
            for (int axis = 0; axis < 3; ++axis) q[3 * c + axis] = coordinates[axis];
        }
        packed_.push_back(q[0] | q[1] << 16);
        packed_.push_back(q[2] | q[3] << 16);
        packed_.push_back(q[4] | q[5] << 16);
        packed_.push_back(q[6] | q[7] << 16);
        packed_.push_back(q[8]);
    }
}

StructureBuffer TriangleStore::buffer() const {
    const std::string what = "triangle vertex (" + std::to_string(triangles_->size()) + " triangles" +
                             (lattice_.bits ? ", packed" : "") + ")";
    if (lattice_.bits) return {what, bytes(), packed_.data()};
    return {what, bytes(), triangles_->data()};
}

std::uint64_t TriangleStore::bytes() const { return triangles_->size() * triangleVertexBytes(lattice_); }

}  // namespace rtbench
