#include "cost_model.h"

#include <algorithm>
#include <cmath>

namespace rtbench {

double surfaceArea(glm::vec3 lo, glm::vec3 hi) {
    const glm::dvec3 e = glm::max(glm::dvec3(hi) - glm::dvec3(lo), glm::dvec3(0.0));
    return 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
}

std::uint64_t raysEnteringBox(const std::vector<gpu::Ray>& rays, glm::vec3 lo, glm::vec3 hi) {
    std::uint64_t entering = 0;
    for (const gpu::Ray& r : rays) {
        double t0 = r.originTMin.w, t1 = r.directionTMax.w;
        bool inside = true;
        for (int a = 0; a < 3 && inside; ++a) {
            const double o = r.originTMin[a], d = r.directionTMax[a];
            if (d == 0.0) {
                inside = o >= lo[a] && o <= hi[a];
                continue;
            }
            const double ta = (lo[a] - o) / d, tb = (hi[a] - o) / d;
            t0 = std::max(t0, std::min(ta, tb));
            t1 = std::min(t1, std::max(ta, tb));
            inside = t0 <= t1;
        }
        entering += inside;
    }
    return entering;
}

}  // namespace rtbench
