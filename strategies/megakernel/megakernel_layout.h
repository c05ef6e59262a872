// The megakernel's own specialization constant, schedules and counters (Parker et al. 2013
// §5.1-5.2), numbered from the ids kernels/gpu_layout.h leaves to a strategy. Included by C++ and
// by GLSL (megakernel.comp).
#ifndef RTBENCH_MEGAKERNEL_LAYOUT_H
#define RTBENCH_MEGAKERNEL_LAYOUT_H

#include "../../kernels/layout_begin.h"

RTBENCH_CONST kSpecSchedule = kSpecStrategyFirst + 0u;  // kSchedule*: how a subgroup picks the state it runs

RTBENCH_CONST kScheduleSwitch = 0;          // each lane runs its own state: the subgroup runs every state present, one after another
RTBENCH_CONST kScheduleIntersectFirst = 1;  // one state per iteration: intersect if any lane waits, else traverse
RTBENCH_CONST kScheduleTraverseFirst = 2;   // one state per iteration: traverse if any lane traverses, else intersect
RTBENCH_CONST kScheduleMajority = 3;        // one state per iteration: the one more lanes are in (a tie: intersect)

RTBENCH_CONST kCountRunsTraverse = kCountStrategyFirst + 0u;   // subgroup executions of the traverse state
RTBENCH_CONST kCountRunsIntersect = kCountStrategyFirst + 1u;  // subgroup executions of the intersect state

#ifdef __cplusplus
static_assert(kCountRunsIntersect < kCountSlots);
#endif
#include "../../kernels/layout_end.h"

#endif  // RTBENCH_MEGAKERNEL_LAYOUT_H
