// The row walk's searches (structures/uniform_grid/voxel_row.h) against a scan of every voxel:
// random spans in random rows, random guesses, and the tests each search asks for.
#include "structures/uniform_grid/voxel_row.h"

#include <gtest/gtest.h>

#include <random>

namespace rtbench {
namespace {

// A row whose voxels [first, last] meet the triangle, counting the voxels asked about.
struct Row {
    int first, last;
    mutable int asked = 0;
    bool operator()(int x) const {
        ++asked;
        return x >= first && x <= last;
    }
};

TEST(VoxelRow, FirstAndLastMeetingAreTheSpansEndsFromAnyGuess) {
    std::mt19937 rng(11);
    for (int trial = 0; trial < 20000; ++trial) {
        const int lo = std::uniform_int_distribution<int>(-5, 5)(rng), length = std::uniform_int_distribution<int>(1, 70)(rng);
        const int hi = lo + length - 1;
        std::uniform_int_distribution<int> inRow(lo, hi), anywhere(lo - 3, hi + 3);
        int first = inRow(rng), last = inRow(rng);
        if (first > last) std::swap(first, last);
        const Row row{first, last};
        const int known = std::uniform_int_distribution<int>(first, last)(rng);
        ASSERT_EQ(firstMeeting(lo, known, anywhere(rng), row), first) << trial;
        ASSERT_EQ(lastMeeting(known, hi, anywhere(rng), row), last) << trial;
    }
}

// Near guesses cost a few tests; far ones about 2 log2 of the row, never a scan.
TEST(VoxelRow, SearchesAskFewVoxels) {
    const Row wide{100, 900};
    EXPECT_EQ(firstMeeting(0, 500, 100, wide), 100);
    EXPECT_LE(wide.asked, 2);
    wide.asked = 0;
    EXPECT_EQ(firstMeeting(0, 500, 101, wide), 100);
    EXPECT_LE(wide.asked, 4);  // 101, 100, 98, 99
    wide.asked = 0;
    EXPECT_EQ(lastMeeting(500, 1023, 0, wide), 900);
    EXPECT_LE(wide.asked, 2 * 10 + 2);
    wide.asked = 0;
    EXPECT_EQ(firstMeeting(0, 500, 500, wide), 100);  // guess at the known voxel: from there down
    EXPECT_LE(wide.asked, 2 * 10 + 2);
}

TEST(VoxelRow, FindSpanFromThePreviousRowOrAScan) {
    std::mt19937 rng(12);
    std::uniform_int_distribution<int> coin(0, 3);
    for (int trial = 0; trial < 20000; ++trial) {
        const int lo = 0, hi = std::uniform_int_distribution<int>(0, 63)(rng);
        std::uniform_int_distribution<int> inRow(lo, hi);
        int first = inRow(rng), last = inRow(rng);
        if (first > last) std::swap(first, last);
        const bool empty = coin(rng) == 0;
        const Row row{empty ? hi + 1 : first, empty ? hi : last};
        VoxelSpan previous;
        if (coin(rng) != 0) {
            previous.first = inRow(rng), previous.last = inRow(rng);
            if (previous.first > previous.last) std::swap(previous.first, previous.last);
        }
        const VoxelSpan span = findSpan(lo, hi, previous, row);
        if (empty) {
            ASSERT_TRUE(span.empty()) << trial;
            ASSERT_EQ(row.asked, (previous.empty() ? 0 : 3) + hi - lo + 1) << trial;  // the guesses, then every voxel
        } else {
            ASSERT_EQ(span.first, first) << trial;
            ASSERT_EQ(span.last, last) << trial;
        }
    }
    // A span that moved one voxel from the previous row's: a handful of tests, not the row's 64.
    const Row moved{11, 41};
    EXPECT_EQ(findSpan(0, 63, VoxelSpan{10, 40}, moved).last, 41);
    EXPECT_LE(moved.asked, 8);
}

}  // namespace
}  // namespace rtbench
