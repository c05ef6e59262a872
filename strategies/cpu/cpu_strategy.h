// The CPU running the same traversal (strategy.type = "cpu"): the structure's own kernels'
// source compiled as C++ (its CPU reference, structures/shared_kernels.h), ray after ray on TBB's
// threads, timed on the host as the kernels are on the device. Christen 2005 §6.2.3 (Figs.
// 6.10-6.11) put his GPU beside a CPU running the same grid algorithm; Embree (the baseline of
// every run) is another algorithm on another structure. Its records are the CPU reference's by
// construction, so they are judged against the exact reference and Embree only; its work counts
// are exact.
#pragma once
#include "strategies/strategy.h"

namespace rtbench {

const StrategyType& cpuStrategyType();

}  // namespace rtbench
