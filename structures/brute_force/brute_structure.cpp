#include "brute_structure.h"

#include <chrono>

#include "brute_reference.h"
#include "structures/shared_source.h"
#include "structures/triangle_store.h"
#include "structures/brute_force/brute_layout.h"
#include "core/error.h"

namespace rtbench {


namespace {

class BruteStructure final : public SharedSourceStructure<bruteref::BruteKernels> {
public:
    // The build time counts from `start`, taken before the members copy and pack the vertices.
    explicit BruteStructure(const TriangleMesh& mesh,
                            std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now())
        : triangles_(floatTriangles(mesh)), vertices_(triangles_, mesh.lattice) {
        params_.counts = glm::uvec4(std::uint32_t(triangles_.size()), 0, 0, 0);
        memoryBytes = vertices_.bytes();
        buildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    }

    std::string kernelPrefix() const override { return "brute_force"; }

    std::vector<StructureBuffer> buffers() const override {
        return {vertices_.buffer()};
    }

    const VertexLattice& vertexLattice() const override { return vertices_.lattice(); }

    StructureCosts costs() const override {
        StructureCosts c;  // no cells, no lists: only the vertices of every triangle
        c.traversalStateBytes = sizeof(gpu::BruteTraversalState);
        c.bytesPerTriangle = triangleVertexBytes(vertexLattice());
        return c;
    }

    bruteref::BruteKernels kernels() const override {
        bruteref::BruteKernels k{};
        vertices_.bind(k);
        k.params = params_;
        return k;
    }

    // One "cell" holding every triangle.
    WalkBounds walkBounds() const override { return {1, triangles_.size()}; }

    // Every ray tests every triangle.
    double predictedWork(const std::vector<gpu::Ray>& rays) const override {
        return double(rays.size()) * double(triangles_.size());
    }

    void writeColumns(Row&) const override {}

private:
    std::vector<gpu::Triangle> triangles_;
    TriangleStore vertices_;  // over triangles_
    gpu::BruteParams params_{};
};

std::unique_ptr<Structure> buildBrute(const TriangleMesh& mesh, const std::vector<gpu::Ray>& rayStream, const RunConfig& run,
                                      const DeviceInfo& device) {
    const std::uint64_t rays = rayStream.size();
    const std::uint64_t tests = rays * mesh.triangles.size();
    const auto limit = std::uint64_t(run.getFloat("structure.max_tests"));
    if (tests > limit)
        throw Error("brute force: " + std::to_string(rays) + " rays x " + std::to_string(mesh.triangles.size()) +
                    " triangles = " + std::to_string(tests) + " ray-triangle tests, over structure.max_tests = " +
                    std::to_string(limit));
    checkBindingSize(device, "triangle vertex (" + std::to_string(mesh.triangles.size()) + " triangles)",
                     mesh.triangles.size() * triangleVertexBytes(mesh.lattice));
    return std::make_unique<BruteStructure>(mesh);
}

}  // namespace

const StructureType& bruteStructureType() {
    static const StructureType type = [] {
        StructureType t;
        t.name = "brute_force";
        t.help = "no structure: every ray tests every triangle";
        t.keys = {
            {"structure.max_tests", ValueType::Float, "brute force: refuse a run of more ray-triangle tests than this (rays x triangles)", 4e9, false, 1, 1e15},
        };
        t.build = buildBrute;
        return t;
    }();
    return type;
}

}  // namespace rtbench
