// Embree 3's device config string ("isa=avx2,threads=4"), checked before Embree sees it: Embree
// ignores what it does not understand (isa=bogus silently runs SSE), so rtbench refuses it.
#pragma once
#include <string>
#include <vector>

namespace rtbench {

// The ISA names rtbench accepts for isa= / max_isa=, widest last.
const std::vector<std::string>& embreeIsaNames();
// Those this CPU can execute (cpuid), e.g. {"sse2", "sse4.2", "avx", "avx2"} on an AVX2 CPU.
std::vector<std::string> embreeIsasSupportedHere();

// Throws rtbench::Error (without file or line: the caller adds them) naming what is wrong and
// what is allowed: keys threads (>= 0), start_threads, set_affinity (0 or 1), verbose (0-3),
// isa / max_isa (a name above that this CPU supports), each key at most once.
void checkEmbreeConfig(const std::string& config);

}  // namespace rtbench
