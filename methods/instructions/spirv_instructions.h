// Static instruction counts of a compiled kernel, per function, from its SPIR-V words: the
// compute half of Purcell et al. 2002's Table 1 ("the number of instructions required to implement
// the kernels"), read from the code the device runs rather than from hand-written assembly.
// Counts are SPIR-V instructions of glslang's unoptimised output (every GLSL function kept as a
// function, locals loaded and stored through memory), not the device's ISA: an estimate, good
// for comparing kernels and architectures compiled the same way.
#pragma once
#include <cstdint>
#include <map>
#include <set>
#include <span>
#include <string>
#include <vector>

namespace rtbench {

class SpirvInstructionCounts {
public:
    // Reads a module; throws rtbench::Error naming what is malformed (the magic number, an
    // instruction running past the end, a call to an unknown function, a function without a name).
    explicit SpirvInstructionCounts(std::span<const std::uint32_t> words);

    // The instructions of `function` (its GLSL name, before glslang's "(" mangling; "main" for the
    // entry point) that do work: every instruction of its body but the declarations and markers
    // (OpFunction, OpFunctionParameter, OpFunctionEnd, OpLabel, OpVariable, OpLine, OpNoLine,
    // OpSelectionMerge, OpLoopMerge), each once however often it runs, every branch counted;
    // each call also counts its callee's, once per call site, except callees named in `leaveOut`
    // (the calls themselves still count). Throws rtbench::Error for a function the module lacks.
    std::uint64_t inclusive(const std::string& function, const std::set<std::string>& leaveOut = {}) const;
    // The function's own instructions, its callees not counted.
    std::uint64_t own(const std::string& function) const;
    bool has(const std::string& function) const { return byName_.count(function) != 0; }

private:
    struct Function {
        std::string name;
        std::uint64_t own = 0;
        std::vector<std::uint32_t> calls;  // callee ids, one per call site
    };
    const Function& named(const std::string& function) const;
    std::uint64_t inclusiveOf(std::uint32_t id, const std::set<std::string>& leaveOut, int depth) const;

    std::map<std::uint32_t, Function> functions_;  // by result id
    std::map<std::string, std::uint32_t> byName_;
};

}  // namespace rtbench
