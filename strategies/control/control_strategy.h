// The control (strategy.type = "control", issue 47 §1): a plain grid ray caster that makes its
// camera rays itself, an 8 x 8 pixel tile per workgroup, and writes 8 bytes a ray
// (strategies/control/kernels/control_grid.comp). It walks and tests as the branching kernel does,
// operation for operation, without the harness's generality (the ray and record buffers, the
// traversal hooks, the specialization constants, exact division), so the two kernels' times on
// the same rays say what that generality costs. It counts no work; its hits are judged against the
// exact reference and Embree, and compared with the CPU reference's (counted, not failed: the
// device divides as it will).
#pragma once
#include "strategies/strategy.h"

namespace rtbench {

const StrategyType& controlStrategyType();

// Rays whose hit (distance and triangle: the control's 8 bytes) differs between two record streams.
std::uint64_t hitPointMismatches(const std::vector<gpu::HitRecord>& a, const std::vector<gpu::HitRecord>& b);

// A bound on the loop iterations any subgroup of the control runs, from the CPU reference's records
// of its rays in row order: per 8 x 8 tile, its rays' voxels and triangle tests summed (a subgroup
// lies within a workgroup, and its lanes in lock step run at most the sum of theirs).
std::uint64_t controlLoopBound(const std::vector<gpu::HitRecord>& cpu, unsigned width, unsigned height);

}  // namespace rtbench
