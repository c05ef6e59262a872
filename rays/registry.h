// The ray types rtbench knows (rays.type), in the order the config schema, the CSV columns and
// the README list them. Adding one is one folder and one line in registry.cpp.
#pragma once
#include <string>
#include <vector>

#include "rays/workload.h"

namespace rtbench {

const std::vector<const RayType*>& rayTypes();
// By config value; throws rtbench::Error naming the value and the known ones.
const RayType& rayType(const std::string& name);

}  // namespace rtbench
