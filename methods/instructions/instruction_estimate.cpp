#include "instruction_estimate.h"

#include "methods/instructions/spirv_instructions.h"
#include "strategies/multipass/multipass_schedule.h"
#include "structures/structure.h"

namespace rtbench {

namespace {

struct PerEvent {
    std::uint64_t step = 0, test = 0;
};

// One step's and one test's instructions as `kernel` has them (0 where it has no such function).
PerEvent perEvent(const SpirvInstructionCounts& kernel, const KernelEvents& events) {
    PerEvent p;
    for (const std::string& f : events.stepFunctions)
        if (kernel.has(f)) p.step += kernel.inclusive(f, events.leaveOut);
    if (kernel.has(kTestFunction)) p.test = kernel.inclusive(kTestFunction, events.leaveOut);
    return p;
}

// The entry point's instructions outside the step and test functions: once per invocation.
std::uint64_t perInvocation(const SpirvInstructionCounts& kernel, const KernelEvents& events) {
    std::set<std::string> outside = events.leaveOut;
    outside.insert(events.stepFunctions.begin(), events.stepFunctions.end());
    outside.insert(kTestFunction);
    return kernel.inclusive("main", outside);
}

}  // namespace

KernelEvents kernelEvents(const Structure& structure, const WorkStats& work) {
    KernelEvents e;
    const StepFunctions step = structure.stepFunctions();
    e.stepFunctions = step.names;
    e.steps = step.perCellVisited ? work.cellsTotal : work.stepsTotal;
    e.tests = work.trianglesTotal;
    e.leaveOut.insert(structure.triangleTest() == gpu::kTriangleTestWatertight ? "rtIntersectTriangle"
                                                                                 : "rtIntersectWatertight");
    if (structure.vertexLattice().bits == 0) e.leaveOut.insert("rtLatticePoint");
    // The division not chosen, and the integer division's rare fallback (non-normal operands).
    e.leaveOut.insert(structure.division() == gpu::kDivisionDouble ? "rtDivideByIntegers" : "rtDivideByDouble");
    return e;
}

InstructionEstimate wholeTraversalInstructions(std::span<const std::uint32_t> words, const KernelEvents& events,
                                               std::uint64_t rays) {
    const SpirvInstructionCounts kernel(words);
    const PerEvent p = perEvent(kernel, events);
    InstructionEstimate e;
    e.known = true;
    e.perStep = p.step;
    e.perTest = p.test;
    e.traverse = events.steps * p.step;
    e.intersect = events.tests * p.test;
    e.other = rays * perInvocation(kernel, events);
    return e;
}

InstructionEstimate multipassInstructions(const MultipassKernelWords& kernels, const KernelEvents& events,
                                          const MultipassCounts& counts, std::uint64_t rays) {
    const SpirvInstructionCounts setup(kernels.setup), traverse(kernels.traverse), intersect(kernels.intersect),
        write(kernels.write);
    InstructionEstimate e;
    e.known = true;
    e.perStep = perEvent(traverse, events).step;
    e.perTest = perEvent(intersect, events).test;
    e.traverse = counts.usefulTraverse * perInvocation(traverse, events) + events.steps * e.perStep;
    e.intersect = counts.usefulIntersect * perInvocation(intersect, events) + events.tests * e.perTest;
    e.other = rays * (perInvocation(setup, events) + perInvocation(write, events));
    return e;
}

}  // namespace rtbench
