// Whether a run's records and counts can be trusted, and if not, the first reason: the last
// judgment of a run (harness/runner.cpp), after its row is written.
#pragma once
#include <cstdint>
#include <string>

#include "strategies/strategy.h"

namespace rtbench {

// The first reason the instrumented run cannot be trusted ("" when none): the device's shading
// passes (`shadingMismatch`), rays cut short, records the CPU reference contradicts, counts,
// multipass's records against branching's, the strategy's two models.
std::string instrumentedRunFailure(const StrategyRun& method, const std::string& shadingMismatch, std::uint64_t rays);

// The timed run's check (KernelTimer::checkHits). Where it fails and the instrumented run had
// already failed, throws that earlier failure, the cause: a kernel that computes wrong records
// need not compute the same wrong ones twice (persistent threads cut short by llvmpipe's loop limit).
void checkTimedRecords(const StrategyRun& method, const std::string& shadingMismatch, std::uint64_t rays);

}  // namespace rtbench
