// Multipass's own specialization constants (Purcell et al. 2002 §3.2; with strategy.control =
// "device", the compacted lists and the oracle kernel), numbered from the ids kernels/gpu_layout.h
// leaves to a strategy. K, M and the suppression of finished reads stay there: every structure's
// multipass hooks read them. Included by C++ and by GLSL (multipass_common.glsl, multipass_oracle.comp).
#ifndef RTBENCH_MULTIPASS_LAYOUT_H
#define RTBENCH_MULTIPASS_LAYOUT_H

#include "../../kernels/layout_begin.h"

RTBENCH_CONST kSpecCompact = kSpecStrategyFirst + 0u;          // 1 = passes serve the rays of a compacted list (control on the device)
RTBENCH_CONST kSpecListPartitions = kSpecStrategyFirst + 1u;   // control on the device: partitions of each ray list (1..kMaxListPartitions)
RTBENCH_CONST kSpecOracleThreshold = kSpecStrategyFirst + 2u;  // oracle kernel: floor(oracle_threshold * 2^31)
RTBENCH_CONST kSpecNaive = kSpecStrategyFirst + 3u;            // oracle kernel: 1 = Christen's naive schedule
RTBENCH_CONST kSpecPassCap = kSpecStrategyFirst + 4u;          // oracle kernel: the pass cap (multipassPassCap)
RTBENCH_CONST kSpecOracleAllRays = kSpecStrategyFirst + 5u;    // oracle kernel: 1 = the threshold's basis is the stream's rays (oracle_basis = all)

#include "../../kernels/layout_end.h"

#endif  // RTBENCH_MULTIPASS_LAYOUT_H
