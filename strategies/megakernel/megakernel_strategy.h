// The scheduled megakernel (Parker et al. 2013, OptiX, §5): strategies/megakernel/megakernel.comp,
// one kernel running each ray's multipass state machine a step at a time, its subgroup choosing
// the state it runs each iteration (strategy.schedule), against the CPU model of the same
// schedule (megakernel_model.h).
#pragma once
#include "strategies/strategy.h"

namespace rtbench {

const StrategyType& megakernelStrategyType();

}  // namespace rtbench
