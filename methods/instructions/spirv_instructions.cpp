#include "spirv_instructions.h"

#include "core/error.h"

namespace rtbench {

namespace {

// SPIR-V 1.x (the Khronos specification, §2.3 and §3.32): a 5-word header, then instructions
// whose first word holds the word count (high 16 bits) and the opcode (low 16 bits).
constexpr std::uint32_t kMagic = 0x07230203u;
constexpr std::uint32_t kOpName = 5, kOpLine = 8, kOpFunction = 54, kOpFunctionParameter = 55, kOpFunctionEnd = 56,
                        kOpFunctionCall = 57, kOpVariable = 59, kOpLoopMerge = 246, kOpSelectionMerge = 247,
                        kOpLabel = 248, kOpNoLine = 317;

bool isWork(std::uint32_t op) {
    switch (op) {
    case kOpFunction: case kOpFunctionParameter: case kOpFunctionEnd: case kOpLabel: case kOpVariable:
    case kOpLine: case kOpNoLine: case kOpSelectionMerge: case kOpLoopMerge:
        return false;
    default:
        return true;
    }
}

// The literal string at words [first, end): UTF-8, nul-terminated, packed four bytes a word.
std::string literalString(std::span<const std::uint32_t> words, std::size_t first, std::size_t end) {
    std::string s;
    for (std::size_t w = first; w < end; ++w)
        for (int b = 0; b < 4; ++b) {
            const char c = char((words[w] >> (8 * b)) & 0xFFu);
            if (c == '\0') return s;
            s += c;
        }
    return s;
}

}  // namespace

SpirvInstructionCounts::SpirvInstructionCounts(std::span<const std::uint32_t> words) {
    if (words.size() < 5 || words[0] != kMagic) throw Error("SPIR-V: not a module (no magic number 0x07230203)");
    std::map<std::uint32_t, std::string> names;
    Function* current = nullptr;
    for (std::size_t at = 5; at < words.size();) {
        const std::uint32_t count = words[at] >> 16, op = words[at] & 0xFFFFu;
        if (count == 0 || at + count > words.size())
            throw Error("SPIR-V: the instruction at word " + std::to_string(at) + " runs past the module's end");
        if (op == kOpName && count >= 3) {
            std::string name = literalString(words, at + 2, at + count);
            names[words[at + 1]] = name.substr(0, name.find('('));  // glslang: "rtDdaStep(struct-RtDda-...;"
        } else if (op == kOpFunction && count >= 3) {
            current = &functions_[words[at + 2]];
        } else if (op == kOpFunctionEnd) {
            current = nullptr;
        } else if (current) {
            if (isWork(op)) current->own += 1;
            if (op == kOpFunctionCall && count >= 4) current->calls.push_back(words[at + 3]);
        }
        at += count;
    }
    for (auto& [id, f] : functions_) {
        const auto name = names.find(id);
        if (name == names.end()) throw Error("SPIR-V: function %" + std::to_string(id) + " has no OpName");
        f.name = name->second;
        byName_[f.name] = id;  // overloads share a GLSL name: the last one stands for it
        for (std::uint32_t callee : f.calls)
            if (!functions_.count(callee)) throw Error("SPIR-V: " + f.name + " calls an unknown function %" + std::to_string(callee));
    }
}

const SpirvInstructionCounts::Function& SpirvInstructionCounts::named(const std::string& function) const {
    const auto it = byName_.find(function);
    if (it == byName_.end()) throw Error("SPIR-V: no function named '" + function + "' in the kernel");
    return functions_.at(it->second);
}

std::uint64_t SpirvInstructionCounts::own(const std::string& function) const { return named(function).own; }

std::uint64_t SpirvInstructionCounts::inclusive(const std::string& function, const std::set<std::string>& leaveOut) const {
    named(function);  // throws for a function the module lacks
    return inclusiveOf(byName_.at(function), leaveOut, 0);
}

std::uint64_t SpirvInstructionCounts::inclusiveOf(std::uint32_t id, const std::set<std::string>& leaveOut, int depth) const {
    // SPIR-V forbids recursion (§2.16.1); a depth past the function count would be a cycle.
    if (depth > int(functions_.size())) throw Error("SPIR-V: the call graph has a cycle");
    const Function& f = functions_.at(id);
    std::uint64_t n = f.own;
    for (std::uint32_t callee : f.calls)
        if (!leaveOut.count(functions_.at(callee).name)) n += inclusiveOf(callee, leaveOut, depth + 1);
    return n;
}

}  // namespace rtbench
