// Brute force as a method's structure (structures/structure.h): no structure at all, every ray
// tests every triangle. The baseline of "no more structure than a scene needs".
#pragma once
#include "structures/structure.h"

namespace rtbench {

const StructureType& bruteStructureType();

}  // namespace rtbench
