// The path megakernel (Laine, Karras & Aila 2013's megakernel, the baseline of their wavefront):
// strategies/path_megakernel/path_megakernel.comp, one dispatch tracing the whole path of every
// camera ray in registers, shading between the traces; the wavefront's peer on the same path.
#pragma once
#include "strategies/strategy.h"

namespace rtbench {

const StrategyType& pathMegakernelStrategyType();

}  // namespace rtbench
