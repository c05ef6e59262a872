// A triangle's voxels along one row of the grid are consecutive. The closed triangle cut by the
// row's slab (the row's cells on the other two axes) is convex, so its projection on the row's
// axis is one interval [a, b]; voxel x, with faces lo[x] <= hi[x] ascending in x, meets it iff
// lo[x] <= b and hi[x] >= a, which holds for every x between two that do. So the builder finds a
// row's two ends with a few exact tests, started from the row before's, and lists the voxels
// between them without testing each (the 2-D walk of a large wall or floor).
#pragma once
#include <algorithm>

namespace rtbench {

// Voxels [first, last] of a row; empty when last < first.
struct VoxelSpan {
    int first = 0, last = -1;
    bool empty() const { return last < first; }
};

// The smallest x in [lo, known] with meets(x), where meets(known) holds and meets, over [lo,
// known], is false then true. Steps out from the guess, doubling, then bisects: a test or two
// when the guess is near, about 2 log2(known - lo) at worst.
template <class Meets>
int firstMeeting(int lo, int known, int guess, const Meets& meets) {
    guess = std::clamp(guess, lo, known);
    int below, above;  // meets(above); below < lo, or !meets(below)
    if (guess == known || meets(guess)) {
        above = guess;
        for (int step = 1;; step *= 2) {
            below = above - step;
            if (below < lo) {
                below = lo - 1;
                break;
            }
            if (!meets(below)) break;
            above = below;
        }
    } else {
        below = guess, above = known;
        for (int step = 1; below + step < above; step *= 2) {
            if (meets(below + step)) {
                above = below + step;
                break;
            }
            below += step;
        }
    }
    while (above - below > 1) {
        const int middle = below + (above - below) / 2;
        (meets(middle) ? above : below) = middle;
    }
    return above;
}

// The largest x in [known, hi] with meets(x), where meets(known) holds and meets, over [known,
// hi], is true then false: firstMeeting on the mirrored row.
template <class Meets>
int lastMeeting(int known, int hi, int guess, const Meets& meets) {
    return -firstMeeting(-hi, -known, -guess, [&](int x) { return meets(-x); });
}

// The span of row [lo, hi] whose voxels meet the triangle. The previous row's span (empty for
// none) gives the guesses: its ends and middle are tried for a voxel that meets, and from one
// the two ends are found. Where none does (or there was no previous span), the row is scanned
// from lo to its first voxel that meets, and its last is found from hi.
template <class Meets>
VoxelSpan findSpan(int lo, int hi, VoxelSpan previous, const Meets& meets) {
    int known = lo - 1;
    if (!previous.empty())
        for (int guess : {previous.first, previous.last, previous.first + (previous.last - previous.first) / 2}) {
            guess = std::clamp(guess, lo, hi);
            if (meets(guess)) {
                known = guess;
                break;
            }
        }
    if (known < lo) {
        for (int x = lo; x <= hi && known < lo; ++x)
            if (meets(x)) known = x;
        return known < lo ? VoxelSpan{} : VoxelSpan{known, lastMeeting(known, hi, hi, meets)};
    }
    return {firstMeeting(lo, known, previous.first, meets), lastMeeting(known, hi, previous.last, meets)};
}

}  // namespace rtbench
