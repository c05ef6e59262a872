// The methods rtbench knows: every structure and every strategy, in the order the config schema,
// the CSV columns and the README list them. Adding a structure is one folder and one line in
// registry.cpp. A method is a structure x a strategy: any with any, but for those that name the one
// they pair with (the driver's acceleration structure and its ray query).
#pragma once
#include <string>
#include <vector>

#include "strategies/strategy.h"
#include "structures/structure.h"

namespace rtbench {

const std::vector<const StructureType*>& structureTypes();
const std::vector<const StrategyType*>& strategyTypes();

// By config value; throws rtbench::Error naming the value and the known ones.
const StructureType& structureType(const std::string& name);
const StrategyType& strategyType(const std::string& name);
// By config value, or null for one rtbench no longer has (an old results folder's).
const StrategyType* findStrategyType(const std::string& name);

// Throws rtbench::Error when the structure and the strategy cannot make a method together (the
// driver's acceleration structure and its ray query go only with each other).
void refuseUnpaired(const StructureType& structure, const StrategyType& strategy);

}  // namespace rtbench
