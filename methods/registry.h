// The methods rtbench knows: every structure and every strategy, in the order the config schema,
// the CSV columns and the README list them. Adding a structure is one folder and one line in
// registry.cpp. A method is any structure x any strategy.
#pragma once
#include <string>
#include <vector>

#include "methods/strategy.h"
#include "methods/structure.h"

namespace rtbench {

const std::vector<const StructureType*>& structureTypes();
const std::vector<const StrategyType*>& strategyTypes();

// By config value; throws rtbench::Error naming the value and the known ones.
const StructureType& structureType(const std::string& name);
const StrategyType& strategyType(const std::string& name);

}  // namespace rtbench
