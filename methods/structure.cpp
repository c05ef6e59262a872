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

}  // namespace rtbench
