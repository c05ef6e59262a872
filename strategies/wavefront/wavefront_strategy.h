// The wavefront (Laine, Karras & Aila 2013): a path's generations traced on the device as queues,
// stage after stage, with no host round trip: the camera rays copied into the queue
// (wavefront_setup.comp), then per generation the structure's whole traversal over the queue
// (wavefront_trace.comp), the shading pass over its slots (wavefront_shade.comp), a scan of the
// rays each workgroup made (wavefront_scan.comp) and their stable compaction into the next queue
// (wavefront_compact.comp); each stage dispatched indirectly with the workgroups the one before
// wrote. Its time is the whole path's; every generation is checked against the CPU's.
#pragma once
#include "strategies/strategy.h"

namespace rtbench {

const StrategyType& wavefrontStrategyType();

}  // namespace rtbench
