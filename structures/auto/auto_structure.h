// structure.type = "auto": builds every other structure with its default keys, predicts each
// one's work on the run's rays with the cost model (structures/cost_model.h), and runs the cheapest.
// The prediction for every candidate is recorded next to what the chosen one measured.
#pragma once
#include "structures/structure.h"

namespace rtbench {

const StructureType& autoStructureType();

}  // namespace rtbench
