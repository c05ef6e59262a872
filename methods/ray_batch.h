// A batch of rays as a workload (harness/workload.h) hands it to a method: the rays, and the query
// they ask of the scene. The method knows no ray type; the query is all it needs of one.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "kernels/gpu_layout.h"

namespace rtbench {

struct RayBatch {
    std::vector<gpu::Ray> rays;
    std::uint32_t query = gpu::kQueryClosest;  // gpu::kQuery*: closest hit or any hit
};

// The query's name, as the rays.query column and the messages write it.
inline const char* queryName(std::uint32_t query) { return query == gpu::kQueryAny ? "any" : "closest"; }

}  // namespace rtbench
