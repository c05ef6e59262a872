// The path megakernel's own counter, numbered from the ids kernels/gpu_layout.h leaves to a
// strategy. Included by C++ and by GLSL (path_megakernel.comp).
#ifndef RTBENCH_PATH_MEGAKERNEL_LAYOUT_H
#define RTBENCH_PATH_MEGAKERNEL_LAYOUT_H

#include "../../kernels/layout_begin.h"

RTBENCH_CONST kCountPathRaysTraced = kCountStrategyFirst + 0u;  // rays traced, every generation's

#ifdef __cplusplus
static_assert(kCountPathRaysTraced < kCountSlots);
#endif
#include "../../kernels/layout_end.h"

#endif  // RTBENCH_PATH_MEGAKERNEL_LAYOUT_H
