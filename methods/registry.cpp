#include "registry.h"

#include "structures/auto/auto_structure.h"
#include "strategies/branching/branching_strategy.h"
#include "strategies/control/control_strategy.h"
#include "structures/brute_force/brute_structure.h"
#include "strategies/cpu/cpu_strategy.h"
#include "structures/bvh/bvh_structure.h"
#include "structures/median_bvh/median_bvh_structure.h"
#include "structures/uniform_grid/grid_structure.h"
#include "strategies/megakernel/megakernel_strategy.h"
#include "strategies/multipass/multipass_strategy.h"
#include "strategies/persistent/persistent_strategy.h"
#include "strategies/plain/plain_strategy.h"
#include "structures/driver/driver_structure.h"
#include "strategies/path_megakernel/path_megakernel_strategy.h"
#include "strategies/ray_query/ray_query_strategy.h"
#include "strategies/sorted/sorted_strategy.h"
#include "strategies/wavefront/wavefront_strategy.h"
#include "core/error.h"

namespace rtbench {

const std::vector<const StructureType*>& structureTypes() {
    static const std::vector<const StructureType*> types = {&gridStructureType(), &bvhStructureType(), &bruteStructureType(),
                                                                  &autoStructureType(), &driverStructureType(),
                                                                  &medianBvhStructureType()};
    return types;
}

const std::vector<const StrategyType*>& strategyTypes() {
    static const std::vector<const StrategyType*> types = {&branchingStrategyType(), &multipassStrategyType(),
                                                                 &persistentStrategyType(), &megakernelStrategyType(),
                                                                 &rayQueryStrategyType(), &plainStrategyType(),
                                                                 &cpuStrategyType(), &wavefrontStrategyType(),
                                                                 &pathMegakernelStrategyType(), &controlStrategyType(),
                                                                 &sortedStrategyType()};
    return types;
}

namespace {
template <class Type>
const Type* find(const std::vector<const Type*>& types, const std::string& name) {
    for (const Type* t : types)
        if (t->name == name) return t;
    return nullptr;
}

template <class Type>
const Type& byName(const std::vector<const Type*>& types, const std::string& name, const char* what) {
    if (const Type* t = find(types, name)) return *t;
    std::string known;
    for (const Type* t : types) known += (known.empty() ? "" : ", ") + t->name;
    throw Error("unknown " + std::string(what) + " '" + name + "' (known: " + known + ")");
}
}  // namespace

const StrategyType* findStrategyType(const std::string& name) { return find(strategyTypes(), name); }

const StructureType& structureType(const std::string& name) { return byName(structureTypes(), name, "structure.type"); }
const StrategyType& strategyType(const std::string& name) { return byName(strategyTypes(), name, "strategy.type"); }

void refuseUnpaired(const StructureType& structure, const StrategyType& strategy) {
    if (!structure.onlyStrategy.empty() && structure.onlyStrategy != strategy.name)
        throw Error("structure.type = " + structure.name + " is traced only by strategy.type = " + structure.onlyStrategy +
                    ", not " + strategy.name);
    if (!strategy.onlyStructure.empty() && strategy.onlyStructure != structure.name)
        throw Error("strategy.type = " + strategy.name + " traces only structure.type = " + strategy.onlyStructure + ", not " +
                    structure.name);
}

}  // namespace rtbench
