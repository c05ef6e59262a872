// Camera rays (rays.type = "primary"): one closest-hit ray through each pixel centre
// (scene/camera.h), the ray casting of Purcell et al. 2002 and Christen 2005.
#pragma once
#include "rays/workload.h"

namespace rtbench {

const RayType& cameraRayType();

}  // namespace rtbench
