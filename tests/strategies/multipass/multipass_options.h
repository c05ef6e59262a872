// The multipass tests' oracle options (test_multipass_kernels.cpp, test_multipass_device_control.cpp).
#pragma once
#include "strategies/multipass/multipass_schedule.h"

namespace rtbench::hand {

// The oracle's options: threshold, K, M, suppression, and where the oracle runs.
inline MultipassOptions multipassOptions(double threshold, unsigned k = 1, unsigned m = 1, bool suppress = false,
                                         bool deviceControl = false) {
    MultipassOptions o;
    o.oracleThreshold = threshold;
    o.traverseStepsPerPass = k;
    o.intersectionsPerPass = m;
    o.suppressFinishedReads = suppress;
    o.deviceControl = deviceControl;
    return o;
}

}  // namespace rtbench::hand
