// Which pass runs next, from the rays active in each state after the last one: Purcell et al.
// 2002 §3.2's oracle (intersect once waiting / active >= the threshold, or waiting / the stream's
// rays with strategy.oracle_basis = all) and Christen 2005 §5.6's
// naive schedule (traverse until no ray traverses, then intersect until none waits). ONE source
// for the host's PassScheduler (multipass_schedule.cpp) and the device's oracle kernel
// (multipass_oracle.comp). The threshold is applied in fixed point, floor(threshold * 2^31)
// (mpThresholdQ31), so host and device decide alike with integers: a ratio decides otherwise than
// in exact arithmetic only within 2^-31 below the threshold (e.g. 1 of 5 waiting meets 0.2).
// kPass* come from kernels/gpu_layout.h.
#ifndef RT_MULTIPASS_ORACLE_GLSL
#define RT_MULTIPASS_ORACLE_GLSL

// `phase`: the naive schedule's current phase, kept between calls. `traversing + waiting` < 2^32.
// `basisRays`: the rays the waiting fraction is of; 0: the active rays (traversing + waiting).
uint mpNextPass(uint traversing, uint waiting, RT_INOUT(uint) phase, uint thresholdQ31, bool naive, uint basisRays) {
    if (traversing + waiting == 0u) return kPassWrite;
    if (waiting == 0u) {
        phase = kPassTraverse;
        return phase;
    }
    if (traversing == 0u) {
        phase = kPassIntersect;
        return phase;
    }
    if (naive) return phase;  // stay in the phase until it drains
    const uint64_t scaledWaiting = uint64_t(waiting) << 31u;
    const uint basis = basisRays != 0u ? basisRays : traversing + waiting;
    return scaledWaiting >= uint64_t(thresholdQ31) * uint64_t(basis) ? kPassIntersect : kPassTraverse;
}

#endif  // RT_MULTIPASS_ORACLE_GLSL
