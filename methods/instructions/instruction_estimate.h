// Purcell et al. 2002's compute (Table 1, Fig. 7, §3.2's cost model): the instructions a frame
// takes, by kernel, as the kernels' static SPIR-V counts (spirv_instructions.h) weighted by the
// run's exact event counts. Purcell's model charges each ray its generation and setup, each voxel
// step and each triangle test its kernel's loop body, and a ray the stencil rejects nothing but
// the stencil read (early fragment kill); so does this one. An estimate, and labelled so: every
// branch of a function counts, and the loop bodies outside the step and test functions (counters,
// a voxel's list bounds, ballots) count once per invocation, not once per iteration.
#pragma once
#include <cstdint>
#include <set>
#include <span>
#include <string>
#include <vector>

#include "methods/metrics.h"

namespace rtbench {

class Structure;
struct MultipassCounts;

struct InstructionEstimate {
    bool known = false;        // false: the strategy's kernels are not estimated (columns left empty)
    std::uint64_t perStep = 0;  // static instructions of one traversal event (Structure::stepFunctions)
    std::uint64_t perTest = 0;  // of one triangle test (rtIntersectStored, the run's test only)
    // Fig. 7's kernels: the traverser, the intersector, the others (ray setup, the record's write).
    std::uint64_t traverse = 0, intersect = 0, other = 0;
    std::uint64_t total() const { return traverse + intersect + other; }
};

// The events of a run and the functions that do them.
struct KernelEvents {
    std::vector<std::string> stepFunctions;  // the structure's traversal event
    std::uint64_t steps = 0;                 // how often it ran
    std::uint64_t tests = 0;                 // triangle tests
    std::set<std::string> leaveOut;          // functions the run's specialization never calls
};

// The function every kernel tests one triangle with (kernels/traversal_common.glsl).
inline constexpr const char* kTestFunction = "rtIntersectStored";

// The run's events and unused functions: the structure's step functions and counter, the triangle
// test it does not run (intersection.test), the packed-vertex decoder when vertices are float.
KernelEvents kernelEvents(const Structure& structure, const WorkStats& work);

// A kernel invoked once per ray (branching): traverse = steps x perStep, intersect = tests x
// perTest, other = rays x the kernel's instructions outside its step and test functions.
InstructionEstimate wholeTraversalInstructions(std::span<const std::uint32_t> kernel, const KernelEvents& events,
                                               std::uint64_t rays);

struct MultipassKernelWords {
    std::span<const std::uint32_t> setup, traverse, intersect, write;
};

// Multipass (Purcell §3.2): each pass kernel runs once per ray its stencil lets through. traverse
// = rays served by traverse passes x the kernel's instructions outside its step functions + steps
// x perStep; intersect likewise with tests; other = rays x (setup's + write's).
InstructionEstimate multipassInstructions(const MultipassKernelWords& kernels, const KernelEvents& events,
                                          const MultipassCounts& counts, std::uint64_t rays);

}  // namespace rtbench
