#include "registry.h"

#include "core/error.h"
#include "rays/ao/ao_rays.h"
#include "rays/primary/primary_rays.h"
#include "rays/path/path_rays.h"
#include "rays/reflection/reflection_rays.h"
#include "rays/refraction/refraction_rays.h"
#include "rays/shadow/shadow_rays.h"
#include "rays/whitted/whitted_rays.h"

namespace rtbench {

const std::vector<const RayType*>& rayTypes() {
    static const std::vector<const RayType*> types = {&cameraRayType(), &shadowRayType(), &reflectionRayType(), &refractionRayType(), &pathRayType(), &aoRayType(), &whittedRayType()};
    return types;
}

const RayType& rayType(const std::string& name) {
    std::string known;
    for (const RayType* t : rayTypes()) {
        if (t->name == name) return *t;
        known += (known.empty() ? "" : ", ") + t->name;
    }
    throw Error("unknown rays.type '" + name + "' (known: " + known + ")");
}

}  // namespace rtbench
