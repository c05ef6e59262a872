// rtbench compare A B: two results folders side by side, as google/benchmark's compare.py and
// nvbench's compare do for benchmarks. Runs are matched by their parameters; per run a verdict
// SAME / FASTER / SLOWER / UNSURE from the kernel's median change, its 95% interval and a
// Mann-Whitney U p-value over the samples (Holm-corrected for the runs compared), Embree's change
// on the same rays (did the machine change?), every count that differs (exact) and the exact
// accuracy on both sides. Folders of an older results schema are compared on what both have.
#pragma once
#include <ostream>
#include <string>
#include <vector>

namespace rtbench {

struct CompareOptions {
    double threshold = 0.05;  // a change counts beyond this fraction of A's median
    double alpha = 0.05;      // ... when the Holm-corrected Mann-Whitney p-value is below this
    bool markdown = false;    // a Markdown table instead of aligned text
    bool json = false;        // JSON (docs/commands.md: compare --json) instead of a table
    // "" judges the kernel's time; "embree1" the kernel's time over Embree rtcIntersect1's on the
    // same rays in the same folder, so that a machine that got slower as a whole is no regression.
    std::string relativeTo;
    std::vector<std::string> ignore;  // config keys not matched on (their runs meet across them)
};

enum class Verdict { Same, Faster, Slower, Unsure };
const char* verdictName(Verdict verdict);  // "SAME", "FASTER", "SLOWER", "UNSURE"

struct ComparedRun {
    std::string key;  // the run's label in A
    std::string runA, runB;
    double medianA = 0.0, medianB = 0.0;       // of the measure: kernel ms, or kernel ms / Embree ms
    double change = 0.0;                       // medianB / medianA - 1
    double changeLow = 0.0, changeHigh = 0.0;  // its 95% interval (NaN without one)
    double p = -1.0, pHolm = -1.0;             // Mann-Whitney U two-sided, raw and Holm; -1 untested
    double embreeChange = 0.0;                 // Embree rtcIntersect1's median change on the same rays
    Verdict verdict = Verdict::Unsure;
    std::string why;                           // what the verdict rests on
    std::vector<std::string> countDifferences;  // "column: a -> b"
    std::string accuracyA, accuracyB;          // exact_wrong_ppm
    bool failed = false;                       // failed on a side: no times compared
    bool flagged = false;                      // a timing warning on a side, or kernel_ms measured two ways
};

struct CompareResult {
    std::vector<ComparedRun> runs;
    std::vector<std::string> onlyA, onlyB;  // "run (label)"
    std::vector<std::string> columnsOnlyA, columnsOnlyB;
    std::vector<std::string> differingKeys;  // "key: A a, b; B c" for keys whose values differ
    int same = 0, faster = 0, slower = 0, unsure = 0, countDifferences = 0;
    // Exit status for CI: 2 when no run matched, 1 on a SLOWER verdict or a count difference, else 0.
    int exitStatus() const { return runs.empty() ? 2 : slower || countDifferences ? 1 : 0; }
};

CompareResult compareFolders(const std::string& folderA, const std::string& folderB, const CompareOptions& options);

// The report: one line (or Markdown row) per matched run, then the unmatched runs and columns; or
// the JSON document.
void printComparison(const CompareResult& result, const std::string& folderA, const std::string& folderB,
                     const CompareOptions& options, std::ostream& out);

}  // namespace rtbench
