#include "path_check.h"

#include <algorithm>

namespace rtbench {

std::uint64_t pathsLeavingWrongHits(const ExactReference& reference, const std::vector<gpu::Ray>& cameraRays,
                                    const Workload& workload, const std::vector<std::uint32_t>& sampled,
                                    bool sameTriangles) {
    // Generation g of the path: 0 the camera rays, g > 0 workload.between[g - 1].
    const std::size_t generations = workload.between.size() + 1;
    // path[g][i]: sampled ray i's ancestor in generation g.
    std::vector<std::vector<std::uint32_t>> path(generations, std::vector<std::uint32_t>(sampled.size()));
    for (std::size_t i = 0; i < sampled.size(); ++i)
        for (std::size_t g = 0; g < generations; ++g) path[g][i] = workload.ancestor(sampled[i], g);
    std::vector<bool> wrong(sampled.size(), false);
    for (std::size_t g = 0; g < generations; ++g) {
        const std::vector<gpu::Ray>& rays = g == 0 ? cameraRays : workload.between[g - 1].rays;
        const std::vector<gpu::HitRecord>& hits = g == 0 ? workload.cameraHits : workload.between[g - 1].hits;
        std::vector<std::uint32_t> ancestors = path[g];
        std::sort(ancestors.begin(), ancestors.end());
        ancestors.erase(std::unique(ancestors.begin(), ancestors.end()), ancestors.end());
        const ExactHits truth = reference.trace(rays, ancestors);
        std::vector<bool> ancestorWrong(ancestors.size());
        for (std::size_t a = 0; a < ancestors.size(); ++a)
            ancestorWrong[a] = truth.judge(a, hits.at(ancestors[a]).primitive, sameTriangles) != ExactHits::Verdict::Right;
        for (std::size_t i = 0; i < sampled.size(); ++i) {
            const auto a = std::lower_bound(ancestors.begin(), ancestors.end(), path[g][i]) - ancestors.begin();
            if (ancestorWrong[std::size_t(a)]) wrong[i] = true;
        }
    }
    return std::uint64_t(std::count(wrong.begin(), wrong.end(), true));
}

}  // namespace rtbench
