// Embree's device config string (harness/embree_config.h), checked before Embree sees it: Embree
// takes the last of a repeated key ("isa=avx2,isa=sse2" runs SSE2), so a repeated key is refused.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "harness/config.h"
#include "harness/embree_config.h"
#include "tests/error_of.h"

namespace rtbench {
namespace {

TEST(EmbreeConfig, AKeyGivenTwiceIsRefusedNamingIt) {
    // Issue 15's string: refused whatever this CPU runs (the keys are checked before the values).
    EXPECT_EQ(errorOf([] { checkEmbreeConfig("isa=avx2,isa=sse2"); }),
              "key 'isa' is given twice in \"isa=avx2,isa=sse2\" (give each key once)");
    EXPECT_EQ(errorOf([] { checkEmbreeConfig("isa=bogus,isa=sse2"); }),
              "key 'isa' is given twice in \"isa=bogus,isa=sse2\" (give each key once)");
    EXPECT_EQ(errorOf([] { checkEmbreeConfig("isa=sse2,isa=sse2"); }),
              "key 'isa' is given twice in \"isa=sse2,isa=sse2\" (give each key once)");
    EXPECT_EQ(errorOf([] { checkEmbreeConfig("threads=1,verbose=0,threads=2"); }),
              "key 'threads' is given twice in \"threads=1,verbose=0,threads=2\" (give each key once)");
    EXPECT_EQ(errorOf([] { checkEmbreeConfig("max_isa=sse2,set_affinity=0,max_isa=sse2"); }),
              "key 'max_isa' is given twice in \"max_isa=sse2,set_affinity=0,max_isa=sse2\" (give each key once)");
    // Refused before the values are judged: verbose=9 alone would be refused for its value.
    EXPECT_EQ(errorOf([] { checkEmbreeConfig("verbose=1,verbose=9"); }),
              "key 'verbose' is given twice in \"verbose=1,verbose=9\" (give each key once)");
}

TEST(EmbreeConfig, DistinctKeysStillPass) {
    EXPECT_EQ(errorOf([] { checkEmbreeConfig("isa=sse2,threads=1,start_threads=0,set_affinity=1,verbose=0"); }),
              "(no error)");
    EXPECT_EQ(errorOf([] { checkEmbreeConfig("isa=sse2,max_isa=sse2"); }), "(no error)");
    EXPECT_EQ(errorOf([] { checkEmbreeConfig(""); }), "(no error)");
}

// The command line's --embree-config goes through the same check.
TEST(EmbreeConfig, TheCommandLineOverrideRefusesARepeatedKey) {
    ExperimentPlan plan;
    EXPECT_EQ(errorOf([&] { overrideEmbreeConfig(plan, "isa=sse2,isa=sse2"); }),
              "--embree-config: key 'isa' is given twice in \"isa=sse2,isa=sse2\" (give each key once)");
}

}  // namespace
}  // namespace rtbench
