#include "registry.h"

#include "methods/auto/auto_structure.h"
#include "methods/branching/branching_strategy.h"
#include "methods/brute/brute_structure.h"
#include "methods/bvh/bvh_structure.h"
#include "methods/grid/grid_structure.h"
#include "methods/megakernel/megakernel_strategy.h"
#include "methods/multipass/multipass_strategy.h"
#include "methods/persistent/persistent_strategy.h"
#include "structures/error.h"

namespace rtbench {

const std::vector<const StructureType*>& structureTypes() {
    static const std::vector<const StructureType*> types = {&gridStructureType(), &bvhStructureType(), &bruteStructureType(),
                                                                  &autoStructureType()};
    return types;
}

const std::vector<const StrategyType*>& strategyTypes() {
    static const std::vector<const StrategyType*> types = {&branchingStrategyType(), &multipassStrategyType(),
                                                                 &persistentStrategyType(), &megakernelStrategyType()};
    return types;
}

namespace {
template <class Type>
const Type& byName(const std::vector<const Type*>& types, const std::string& name, const char* what) {
    std::string known;
    for (const Type* t : types) {
        if (t->name == name) return *t;
        known += (known.empty() ? "" : ", ") + t->name;
    }
    throw Error("unknown " + std::string(what) + " '" + name + "' (known: " + known + ")");
}
}  // namespace

const StructureType& structureType(const std::string& name) { return byName(structureTypes(), name, "structure.type"); }
const StrategyType& strategyType(const std::string& name) { return byName(strategyTypes(), name, "strategy.type"); }

}  // namespace rtbench
