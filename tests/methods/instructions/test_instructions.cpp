// The instruction estimate (methods/instructions): static counts on a hand-assembled SPIR-V module
// whose instruction mix is known, the weighting by event counts by hand, the same GLSL function
// counted alike in every kernel that compiles it, and the columns of a run.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "device/embedded_kernels.h"
#include "methods/instructions/instruction_estimate.h"
#include "methods/instructions/spirv_instructions.h"
#include "strategies/multipass/multipass_schedule.h"
#include "core/error.h"
#include "tests/error_of.h"
#include "scene/procedural.h"
#include "tests/harness/test_experiment.h"
#include "tests/methods/hand_scenes.h"

namespace rtbench {
namespace {

using ::testing::HasSubstr;

// A SPIR-V module written by hand, instruction by instruction.
struct Module {
    std::vector<std::uint32_t> words = {0x07230203u, 0x00010000u, 0u, 100u, 0u};
    void op(std::uint32_t opcode, std::vector<std::uint32_t> operands) {
        words.push_back(std::uint32_t(operands.size() + 1) << 16 | opcode);
        words.insert(words.end(), operands.begin(), operands.end());
    }
    void name(std::uint32_t id, const std::string& s) {  // OpName: the string, nul-terminated, 4 bytes a word
        std::vector<std::uint32_t> operands = {id};
        for (std::size_t i = 0; i <= s.size(); i += 4) {
            std::uint32_t w = 0;
            for (std::size_t b = 0; b < 4 && i + b < s.size(); ++b) w |= std::uint32_t(std::uint8_t(s[i + b])) << (8 * b);
            operands.push_back(w);
        }
        op(5, operands);
    }
};

// Opcodes (SPIR-V specification §3.32).
constexpr std::uint32_t kLine = 8, kTypeVoid = 19, kTypeInt = 21, kTypeFunction = 33, kConstant = 43, kFunction = 54,
                        kFunctionEnd = 56, kCall = 57, kVariable = 59, kIAdd = 128, kLoopMerge = 246,
                        kSelectionMerge = 247, kLabel = 248, kReturn = 253;

// main calls step twice and rtIntersectStored once, which calls unused. Work instructions, by
// hand: step 3 adds + return = 4; unused 10 adds + return = 11; rtIntersectStored 2 adds + a call
// + return = 4; main 1 add + 3 calls + return = 5 (labels, variables, merges and lines not counted).
std::vector<std::uint32_t> handModule() {
    Module m;
    m.name(10, "main");
    m.name(11, "step(i1;");
    m.name(12, "rtIntersectStored(struct-RtTriangleRay-vf3-vf3-f11;u1;f1;f1;f1;");
    m.name(13, "unused(");
    m.op(kTypeVoid, {1});
    m.op(kTypeFunction, {2, 1});
    m.op(kTypeInt, {3, 32, 1});
    m.op(kConstant, {3, 4, 1});
    auto function = [&m](std::uint32_t id, int adds, std::vector<std::uint32_t> calls) {
        m.op(kFunction, {1, id, 0, 2});
        m.op(kLabel, {50 + id});
        m.op(kVariable, {3, 60 + id, 7});
        m.op(kLine, {1, 2, 3});
        for (int i = 0; i < adds; ++i) m.op(kIAdd, {3, 70, 4, 4});
        for (std::uint32_t callee : calls) m.op(kCall, {1, 80, callee});
        m.op(kSelectionMerge, {90, 0});
        m.op(kLoopMerge, {91, 92, 0});
        m.op(kReturn, {});
        m.op(kFunctionEnd, {});
    };
    function(11, 3, {});
    function(13, 10, {});
    function(12, 2, {13});
    function(10, 1, {11, 11, 12});
    return m.words;
}

TEST(SpirvInstructionCounts, CountsAHandModulesWorkByFunction) {
    const std::vector<std::uint32_t> words = handModule();
    const SpirvInstructionCounts counts(words);
    EXPECT_EQ(counts.own("main"), 5u);
    EXPECT_EQ(counts.own("step"), 4u);
    EXPECT_EQ(counts.own(kTestFunction), 4u);
    EXPECT_EQ(counts.inclusive("unused"), 11u);
    EXPECT_EQ(counts.inclusive(kTestFunction), 15u);
    EXPECT_EQ(counts.inclusive("main"), 5u + 2u * 4u + 15u);             // step at both call sites
    EXPECT_EQ(counts.inclusive("main", {"unused"}), 5u + 2u * 4u + 4u);  // the call itself still counts
    EXPECT_EQ(counts.inclusive("main", {"step", kTestFunction}), 5u);
    EXPECT_FALSE(counts.has("absent"));
    EXPECT_THAT(errorOf([&] { counts.inclusive("absent"); }), HasSubstr("no function named 'absent'"));
}

TEST(SpirvInstructionCounts, RefusesWhatIsNotAWholeModule) {
    std::vector<std::uint32_t> words = handModule();
    EXPECT_THAT(errorOf([&] { SpirvInstructionCounts(std::span<const std::uint32_t>(words.data(), 4)); }),
                HasSubstr("not a module"));
    words[0] = 0x03022307u;  // the magic number byte-swapped
    EXPECT_THAT(errorOf([&] { SpirvInstructionCounts{words}; }), HasSubstr("not a module"));
    words = handModule();
    words.push_back(5u << 16 | kIAdd);  // an instruction of 5 words with 1 left
    EXPECT_THAT(errorOf([&] { SpirvInstructionCounts{words}; }), HasSubstr("runs past the module's end"));
    Module m;
    m.op(kFunction, {1, 10, 0, 2});
    m.op(kCall, {1, 80, 99});
    m.op(kFunctionEnd, {});
    m.name(10, "main");
    EXPECT_THAT(errorOf([&] { SpirvInstructionCounts{m.words}; }), HasSubstr("main calls an unknown function %99"));
}

TEST(InstructionEstimate, WeightsTheStaticCountsByTheEvents) {
    const std::vector<std::uint32_t> words = handModule();
    KernelEvents events;
    events.stepFunctions = {"step"};
    events.steps = 10;
    events.tests = 3;
    events.leaveOut = {"unused"};
    const InstructionEstimate branching = wholeTraversalInstructions(words, events, /*rays=*/2);
    EXPECT_TRUE(branching.known);
    EXPECT_EQ(branching.perStep, 4u);
    EXPECT_EQ(branching.perTest, 4u);
    EXPECT_EQ(branching.traverse, 10u * 4u);
    EXPECT_EQ(branching.intersect, 3u * 4u);
    EXPECT_EQ(branching.other, 2u * 5u);
    EXPECT_EQ(branching.total(), 62u);
    // Multipass: the same module for all four kernels; 7 rays served by traverse passes, 5 by
    // intersect passes, each paying main's 5 besides its events.
    MultipassCounts counts;
    counts.usefulTraverse = 7;
    counts.usefulIntersect = 5;
    const InstructionEstimate multipass = multipassInstructions({words, words, words, words}, events, counts, 2);
    EXPECT_EQ(multipass.traverse, 7u * 5u + 10u * 4u);
    EXPECT_EQ(multipass.intersect, 5u * 5u + 3u * 4u);
    EXPECT_EQ(multipass.other, 2u * (5u + 5u));
}

// A run's events: the grid counts its DDA steps, the BVH its inner nodes (cells visited) (brute
// force: none, EveryBranchingAndMultipassRunWritesItsColumns); the test the run does not use and, for float vertices, the packed decoder are
// left out.
TEST(InstructionEstimate, EachStructureNamesItsEventAndItsCounter) {
    const TriangleMesh scene = christenSceneA();
    WorkStats work;
    work.stepsTotal = 11;
    work.cellsTotal = 7;
    work.trianglesTotal = 5;
    const std::unique_ptr<Structure> grid = gridStructure(hand::gridOf(scene, {4, 4, 4}));
    const std::unique_ptr<Structure> bvh = bvhStructure(hand::bvhOf(scene, 2));
    KernelEvents e = kernelEvents(*grid, work);
    EXPECT_EQ(e.stepFunctions, std::vector<std::string>{"rtDdaStep"});
    EXPECT_EQ(e.steps, 11u);
    EXPECT_EQ(e.tests, 5u);
    EXPECT_EQ(e.leaveOut, (std::set<std::string>{"rtIntersectWatertight", "rtLatticePoint", "rtDivideByIntegers"}));
    e = kernelEvents(*bvh, work);
    EXPECT_EQ(e.stepFunctions, std::vector<std::string>{"rtBvhChildren"});
    EXPECT_EQ(e.steps, 7u);
    bvh->setArithmetic({gpu::kTriangleTestWatertight, gpu::kDivisionInteger});
    EXPECT_EQ(kernelEvents(*bvh, work).leaveOut,
              (std::set<std::string>{"rtIntersectTriangle", "rtLatticePoint", "rtDivideByDouble"}));
}

// The same GLSL function compiles to the same instructions in every kernel: a step or a test costs
// the branching kernel what it costs the multipass kernels (a second reading of the counts, module
// by module, that a wrong function lookup or call walk would make disagree).
TEST(InstructionEstimate, AFunctionCostsTheSameInEveryKernel) {
    for (const auto& [prefix, step] : {std::pair<std::string, std::string>{"uniform_grid", "rtDdaStep"}, {"bvh", "rtBvhChildren"}}) {
        SCOPED_TRACE(prefix);
        const SpirvInstructionCounts branching(embeddedKernel(prefix + "_branching")),
            traverse(embeddedKernel(prefix + "_multipass_traverse")),
            intersect(embeddedKernel(prefix + "_multipass_intersect"));
        EXPECT_EQ(branching.inclusive(step), traverse.inclusive(step));
        const std::set<std::string> watertightOff = {"rtIntersectWatertight", "rtLatticePoint"};
        EXPECT_EQ(branching.inclusive(kTestFunction, watertightOff), intersect.inclusive(kTestFunction, watertightOff));
        // Leaving the unused test out takes exactly its instructions off.
        EXPECT_EQ(branching.inclusive(kTestFunction) - branching.inclusive(kTestFunction, {"rtIntersectWatertight"}),
                  branching.inclusive("rtIntersectWatertight"));
        EXPECT_GT(branching.inclusive(step), 10u);
        EXPECT_LT(branching.inclusive(step), branching.inclusive("main"));
    }
}

TEST(InstructionEstimate, EveryBranchingAndMultipassRunWritesItsColumns) {
    TempDir dir;
    const ExperimentResult result = runTestConfig(
        dir, "instructions",
        "[scene]\nsource = \"procedural:christen_b\"\n[camera]\nwidth = 32\nheight = 24\n"
        "[structure]\ntype = [\"uniform_grid\", \"bvh\", \"brute_force\"]\nmin_dim = 8\n"
        "[strategy]\ntype = [\"branching\", \"multipass\"]\n");
    ASSERT_EQ(result.rows.size(), 6u);
    std::map<std::string, std::string> perTest;
    for (const Row& row : result.rows) {
        const auto number = [&](const char* key) { return std::stoull(cellText(row, key)); };
        SCOPED_TRACE(cellText(row, "label"));
        ASSERT_EQ(cellText(row, "status"), "ok") << cellText(row, "error");
        EXPECT_EQ(number("instructions_total"),
                  number("instructions_traverse") + number("instructions_intersect") + number("instructions_other"));
        EXPECT_GT(number("instructions_intersect"), 0u);
        // Brute force takes no traversal steps.
        EXPECT_EQ(number("instructions_per_step") == 0, cellText(row, "structure_type") == "brute_force");
        // A test costs the two architectures alike.
        auto [it, added] = perTest.emplace(cellText(row, "structure_type"), cellText(row, "instructions_per_test"));
        if (!added) {
            EXPECT_EQ(it->second, cellText(row, "instructions_per_test"));
        }
    }
}

}  // namespace
}  // namespace rtbench
