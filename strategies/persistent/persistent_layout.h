// Persistent threads' own specialization constants and counters (Aila & Laine 2009), numbered
// from the ids kernels/gpu_layout.h leaves to a strategy. Included by C++ and by GLSL
// (persistent.comp).
#ifndef RTBENCH_PERSISTENT_LAYOUT_H
#define RTBENCH_PERSISTENT_LAYOUT_H

#include "../../kernels/layout_begin.h"

RTBENCH_CONST kSpecRaysPerFetch = kSpecStrategyFirst + 0u;          // rays a subgroup fetches at a time (a multiple of its size)
RTBENCH_CONST kSpecMaxFetches = kSpecStrategyFirst + 1u;            // fetches a subgroup makes at most (0: until the stream is done)
RTBENCH_CONST kSpecPersistentWorkgroups = kSpecStrategyFirst + 2u;  // the workgroups asked for (a 2-D grid may pad beyond them)

RTBENCH_CONST kCountRaysFetched = kCountStrategyFirst + 0u;  // the ray-fetch counter (rays handed out, overshoot included)
RTBENCH_CONST kCountRaysTraced = kCountStrategyFirst + 1u;   // rays whose record a lane wrote

#ifdef __cplusplus
static_assert(kCountRaysTraced < kCountSlots);
#endif
#include "../../kernels/layout_end.h"

#endif  // RTBENCH_PERSISTENT_LAYOUT_H
