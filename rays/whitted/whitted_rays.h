// Whitted ray tracing (rays.type = "whitted"; Whitted 1980, Purcell et al. 2002 Fig. 3c and
// Table 3): each hit, by its surface's material, makes a shadow ray toward every point light
// (diffuse surfaces and mirrors' diffuse part), its mirror reflection (mirrors and glass) and its
// refraction (glass: Fresnel's split, total internal reflection past the critical angle), each
// ray carrying the weight its radiance adds to the pixel with instead of a recursion (Christen
// 2005 §5.2.1). Generation k holds the reflections and refractions of generation k - 1's hits
// (0: the camera rays), traced by the run's structure, closest hit. A run measures one batch:
// generation whitted.depth (whitted.rays = secondary) or the shadow rays of its hits
// (whitted.rays = shadow, any hit); Purcell's Whitted cost is the sum over the batches of a depth.
// Materials and lights come from a scene description ([[material]], [[light]];
// scene/appearance.h), the rest of the scene taking whitted.surface, the lights else
// light.position.
#pragma once
#include "rays/workload.h"

namespace rtbench {

const RayType& whittedRayType();

// The run's materials and lights for its shading passes: material 0 the run's whitted.surface,
// 1 + m the description's material m; the lights moved into the traced scene. Throws
// rtbench::Error naming the key for what cannot be.
std::shared_ptr<const Surfaces> whittedSurfaces(const WorkloadInputs& in);

}  // namespace rtbench
