#include "structure.h"

namespace rtbench {

std::vector<gpu::HitRecord> Structure::trace(const std::vector<gpu::Ray>& rays, std::uint32_t query) const {
    return std::visit(
        [&](auto kernels) {
            kernels.query = query;
            return traceAll(kernels, rays);
        },
        cpuKernels());
}

KernelSpec structureKernelSpec(const Structure& structure, unsigned workgroupSize, std::uint32_t query,
                               std::vector<SpecializationConstant> constants) {
    KernelSpec spec;
    spec.workgroupSize = workgroupSize;
    spec.triangleTest = structure.triangleTest();
    spec.division = structure.division();
    spec.vertexLattice = structure.vertexLattice();
    spec.query = query;
    spec.strategyConstants = std::move(constants);
    return spec;
}

}  // namespace rtbench
