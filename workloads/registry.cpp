#include "registry.h"

#include "core/error.h"
#include "workloads/ao/ao_rays.h"
#include "workloads/camera/camera_rays.h"
#include "workloads/path/path_rays.h"
#include "workloads/reflection/reflection_rays.h"
#include "workloads/refraction/refraction_rays.h"
#include "workloads/shadow/shadow_rays.h"
#include "workloads/whitted/whitted_rays.h"

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
