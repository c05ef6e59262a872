// rtbench compare A B: two results folders side by side, as google/benchmark's compare.py does
// for benchmarks. Runs are matched by their parameters; per run: the change of the kernel's median
// time with its bootstrap interval and a Mann-Whitney U p-value over the samples, Embree's change
// on the same rays (did the machine change?), every count that differs (exact) and the exact
// accuracy on both sides. Folders of an older results schema are compared on what both have.
#pragma once
#include <ostream>
#include <string>
#include <vector>

namespace rtbench {

struct CompareOptions {
    double threshold = 0.05;  // a slowdown counts when B's median is more than this fraction slower
    double alpha = 0.05;      // ... and the Mann-Whitney p-value is below this
    bool markdown = false;    // a Markdown table instead of aligned text
};

struct ComparedRun {
    std::string key;    // the matched parameters, as "key=value ..." (those that vary across A)
    std::string runA, runB;
    double medianA = 0.0, medianB = 0.0;  // kernel ms
    double change = 0.0;                  // medianB / medianA - 1
    double changeLow = 0.0, changeHigh = 0.0;  // 95% bootstrap interval of the change (samples)
    double p = -1.0;                      // Mann-Whitney U two-sided; -1 without samples
    double embreeChange = 0.0;            // Embree rtcIntersect1's median change on the same rays
    bool regression = false, improvement = false;  // significant beyond the threshold
    std::vector<std::string> countDifferences;      // "column: a -> b"
    std::string accuracyA, accuracyB;               // exact_wrong_ppm
    std::string note;                               // failed rows, missing samples, noise warnings
};

struct CompareResult {
    std::vector<ComparedRun> runs;
    std::vector<std::string> onlyA, onlyB;          // "run (label)"
    std::vector<std::string> columnsOnlyA, columnsOnlyB;
    int regressions = 0, improvements = 0, countDifferences = 0;
    // Exit status for CI: 1 on a significant regression or a count difference, else 0.
    int exitStatus() const { return regressions || countDifferences ? 1 : 0; }
};

CompareResult compareFolders(const std::string& folderA, const std::string& folderB, const CompareOptions& options);

// The report: one line (or Markdown row) per matched run, then the unmatched runs and columns.
void printComparison(const CompareResult& result, const std::string& folderA, const std::string& folderB,
                     const CompareOptions& options, std::ostream& out);

}  // namespace rtbench
