#include "run_verdict.h"

#include "core/error.h"

namespace rtbench {

std::string instrumentedRunFailure(const StrategyRun& method, const std::string& shadingMismatch, std::uint64_t rays) {
    std::string why;
    if (!shadingMismatch.empty())
        why = shadingMismatch;
    else if (method.truncatedRays)
        why = method.truncatedWhy;
    else if (method.cpuMismatches)
        why = "the kernel's hit records differ from the CPU reference's on " + std::to_string(method.cpuMismatches) +
              " of " + std::to_string(rays) + " rays";
    else if (!method.countsMismatch.empty())
        why = "the kernel's " + method.countsMismatch + " from the CPU reference's";
    else if (method.branchingMismatches)
        why = "the multipass hit records differ from the branching caster's on " +
              std::to_string(method.branchingMismatches) + " of " + std::to_string(rays) + " rays";
    else if (!method.modelMismatch.empty())
        why = method.modelMismatch;
    return why;
}

void checkTimedRecords(const StrategyRun& method, const std::string& shadingMismatch, std::uint64_t rays) {
    try {
        method.timer->checkHits();
    } catch (const Error&) {
        const std::string earlier = instrumentedRunFailure(method, shadingMismatch, rays);
        if (earlier.empty()) throw;
        throw Error(earlier + "; the timed run's records differ from the instrumented run's too");
    }
}

}  // namespace rtbench
