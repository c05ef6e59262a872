#include "compare.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <map>
#include <set>
#include <sstream>

#include "columns.h"
#include "config.h"
#include "statistics.h"
#include "structures/error.h"
#include "timing_rounds.h"

namespace rtbench {
namespace fs = std::filesystem;

namespace {

// One side: its rows, its header and its samples by "run|config_hash|method".
struct Side {
    std::vector<Row> rows;
    std::set<std::string> columns;
    std::map<std::string, std::vector<double>> samples;
};

Side load(const std::string& folder) {
    std::error_code ec;
    if (!fs::is_directory(folder, ec)) throw Error(folder + ": not a results folder (no such folder)");
    const std::string csv = (fs::path(folder) / "runs.csv").string();
    if (!fs::exists(fs::symlink_status(csv, ec)))
        throw Error(csv + ": not found (not a results folder, or its shards are not merged yet)");
    Side side;
    side.rows = readRunsCsv(csv);
    if (!side.rows.empty())
        for (const auto& [column, value] : side.rows.front()) side.columns.insert(column);
    const std::string samples = (fs::path(folder) / "samples.csv").string();
    if (fs::exists(fs::symlink_status(samples, ec))) {
        for (const Row& s : readSamplesCsv(samples)) {
            const double ms = cellNumber(s.at("ms"));
            if (std::isnan(ms)) throw Error(samples + ": run " + s.at("run") + ": ms '" + s.at("ms") + "' is not a number");
            side.samples[s.at("run") + "|" + s.at("config_hash") + "|" + s.at("method")].push_back(ms);
        }
    }
    return side;
}

std::string get(const Row& row, const std::string& column) {
    const auto it = row.find(column);
    return it == row.end() ? std::string() : it->second;
}

// A run's samples of one method; none when the folder (or the run) has none.
std::vector<double> timesOf(const Side& side, const Row& row, const std::string& method) {
    const auto it = side.samples.find(get(row, "run") + "|" + get(row, "config_hash") + "|" + method);
    if (it != side.samples.end()) return it->second;
    return {};
}

std::string percent(double fraction) {
    if (!std::isfinite(fraction)) return "-";
    std::ostringstream s;
    s << std::showpos << std::fixed << std::setprecision(1) << 100.0 * fraction << "%";
    return s.str();
}

// The columns that identify a run's work: its config keys, but not where the results went or how
// they were timed (experiment.*) nor the device (compare one config across devices).
bool isMatchKey(const std::string& column, const std::set<std::string>& parameterColumns) {
    return parameterColumns.count(column) && column.rfind("experiment_", 0) != 0 && column.rfind("device_", 0) != 0;
}

}  // namespace

CompareResult compareFolders(const std::string& folderA, const std::string& folderB, const CompareOptions& options) {
    if (!(options.threshold >= 0) || !(options.alpha > 0 && options.alpha <= 1))
        throw Error("compare: --threshold must be >= 0 and --alpha in (0, 1]");
    const Side a = load(folderA), b = load(folderB);
    CompareResult result;
    for (const std::string& c : a.columns)
        if (!b.columns.count(c)) result.columnsOnlyA.push_back(c);
    for (const std::string& c : b.columns)
        if (!a.columns.count(c)) result.columnsOnlyB.push_back(c);

    std::set<std::string> parameterColumns;
    for (const KeySpec& k : configSchema())
        for (const std::string& c : keyColumns(k)) parameterColumns.insert(c);
    // Matched on the key columns both files have, in declared order.
    std::vector<std::string> matchOn;
    for (const std::string& c : runColumns())
        if (isMatchKey(c, parameterColumns) && a.columns.count(c) && b.columns.count(c)) matchOn.push_back(c);
    auto keyOf = [&](const Row& row) {
        std::string key;
        for (const std::string& c : matchOn) key += c + "=" + get(row, c) + ";";
        return key;
    };
    std::map<std::string, std::vector<const Row*>> inB;
    for (const Row& row : b.rows) inB[keyOf(row)].push_back(&row);
    std::map<std::string, std::size_t> taken;  // the k-th A row of a key meets the k-th B row
    std::set<const Row*> matchedB;
    for (const Row& rowA : a.rows) {
        const std::string key = keyOf(rowA);
        const auto candidates = inB.find(key);
        const std::size_t k = taken[key]++;
        if (candidates == inB.end() || k >= candidates->second.size()) {
            result.onlyA.push_back(get(rowA, "run") + " (" + get(rowA, "label") + ")");
            continue;
        }
        const Row& rowB = *candidates->second[k];
        matchedB.insert(&rowB);
        ComparedRun run;
        run.key = get(rowA, "label");
        run.runA = get(rowA, "run");
        run.runB = get(rowB, "run");
        run.accuracyA = get(rowA, "exact_wrong_ppm");
        run.accuracyB = get(rowB, "exact_wrong_ppm");
        const bool okA = get(rowA, "status") == "ok", okB = get(rowB, "status") == "ok";
        if (!okA || !okB) {
            run.note = std::string(okA ? "" : "failed in A") + (!okA && !okB ? ", " : "") + (okB ? "" : "failed in B");
            result.runs.push_back(run);
            continue;
        }
        // Counts: deterministic, compared exactly (the columns both files have).
        for (const ColumnSpec& c : runColumnSpecs())
            if (c.kind == ColumnKind::Exact && c.name != "error" && c.name != "warnings" && a.columns.count(c.name) &&
                b.columns.count(c.name) &&
                get(rowA, c.name) != get(rowB, c.name))
                run.countDifferences.push_back(c.name + ": " + get(rowA, c.name) + " -> " + get(rowB, c.name));
        result.countDifferences += int(run.countDifferences.size());

        // Time: the samples when both folders have them, else the rows' medians (no test).
        const std::vector<double> kernelA = timesOf(a, rowA, "kernel"), kernelB = timesOf(b, rowB, "kernel");
        const std::vector<double> embreeA = timesOf(a, rowA, "embree1"), embreeB = timesOf(b, rowB, "embree1");
        const bool sampled = !kernelA.empty() && !kernelB.empty();
        run.medianA = sampled ? median(kernelA) : cellNumber(get(rowA, "kernel_ms_median"));
        run.medianB = sampled ? median(kernelB) : cellNumber(get(rowB, "kernel_ms_median"));
        run.change = run.medianB / run.medianA - 1.0;
        const double embreeMedianA = !embreeA.empty() ? median(embreeA) : cellNumber(get(rowA, "embree1_ms_median"));
        const double embreeMedianB = !embreeB.empty() ? median(embreeB) : cellNumber(get(rowB, "embree1_ms_median"));
        run.embreeChange = embreeMedianB / embreeMedianA - 1.0;
        if (sampled) {
            const Interval ratio = bootstrapRatioOfMedians(kernelB, kernelA);
            run.changeLow = ratio.low - 1.0;
            run.changeHigh = ratio.high - 1.0;
            run.p = mannWhitneyU(kernelB, kernelA).p;
            run.regression = run.p < options.alpha && run.change > options.threshold;
            run.improvement = run.p < options.alpha && run.change < -options.threshold;
        } else {
            run.changeLow = run.changeHigh = std::nan("");
            run.note = std::string("no samples of this run in ") +
                       (kernelA.empty() && kernelB.empty() ? "A and B" : kernelA.empty() ? "A" : "B") +
                       " (no samples.csv before results schema 5): medians only, no test";
        }
        if (!get(rowA, "timing_warning").empty() || !get(rowB, "timing_warning").empty())
            run.note += std::string(run.note.empty() ? "" : "; ") + "timing_warning on " +
                        (get(rowA, "timing_warning").empty() ? "B" : get(rowB, "timing_warning").empty() ? "A" : "both");
        result.regressions += run.regression;
        result.improvements += run.improvement;
        result.runs.push_back(run);
    }
    for (const Row& row : b.rows)
        if (!matchedB.count(&row)) result.onlyB.push_back(get(row, "run") + " (" + get(row, "label") + ")");
    return result;
}

void printComparison(const CompareResult& result, const std::string& folderA, const std::string& folderB,
                     const CompareOptions& options, std::ostream& out) {
    auto fixed = [](double v, int digits) {
        if (!std::isfinite(v)) return std::string("-");
        std::ostringstream s;
        s << std::fixed << std::setprecision(digits) << v;
        return s.str();
    };
    const std::vector<std::string> header = {"A", "B", "parameters", "kernel ms A", "kernel ms B", "change", "95% interval",
                                             "p (U test)", "Embree1 change", "wrong ppm A / B", "verdict"};
    std::vector<std::vector<std::string>> table;
    for (const ComparedRun& r : result.runs) {
        const bool failed = r.note.rfind("failed", 0) == 0;
        const std::string verdict = failed                           ? r.note
                                    : r.regression                   ? "SLOWER"
                                    : r.improvement                  ? "faster"
                                    : r.p < 0                        ? "no test"
                                                                     : "no significant change";
        table.push_back({r.runA, r.runB, r.key, failed ? "-" : fixed(r.medianA, 4), failed ? "-" : fixed(r.medianB, 4),
                         failed ? "-" : percent(r.change),
                         std::isfinite(r.changeLow) && !failed ? "[" + percent(r.changeLow) + ", " + percent(r.changeHigh) + "]" : "-",
                         r.p < 0 ? "-" : fixed(r.p, 4), failed ? "-" : percent(r.embreeChange),
                         (r.accuracyA.empty() ? "-" : r.accuracyA) + " / " + (r.accuracyB.empty() ? "-" : r.accuracyB),
                         verdict});
    }
    out << "rtbench compare " << folderA << " (A) -> " << folderB << " (B): " << result.runs.size() << " runs matched by their parameters";
    if (!result.onlyA.empty() || !result.onlyB.empty())
        out << " (" << result.onlyA.size() << " only in A, " << result.onlyB.size() << " only in B)";
    out << "\n";
    if (options.markdown) {
        out << "\n|";
        for (const std::string& h : header) out << " " << h << " |";
        out << "\n|";
        for (std::size_t i = 0; i < header.size(); ++i) out << "---|";
        out << "\n";
        for (const auto& row : table) {
            out << "|";
            for (const std::string& cell : row) out << " " << cell << " |";
            out << "\n";
        }
        out << "\n";
    } else {
        std::vector<std::size_t> width(header.size());
        for (std::size_t c = 0; c < header.size(); ++c) {
            width[c] = header[c].size();
            for (const auto& row : table) width[c] = std::max(width[c], row[c].size());
        }
        auto line = [&](const std::vector<std::string>& cells) {
            for (std::size_t c = 0; c < cells.size(); ++c)
                out << std::left << std::setw(int(width[c])) << cells[c] << (c + 1 < cells.size() ? "  " : "\n");
        };
        line(header);
        for (const auto& row : table) line(row);
    }
    for (const ComparedRun& r : result.runs) {
        for (const std::string& d : r.countDifferences)
            out << "count differs: run " << r.runA << " -> " << r.runB << " (" << r.key << "): " << d << "\n";
        if (!r.note.empty() && r.note.rfind("failed", 0) != 0) out << "note: run " << r.runA << " (" << r.key << "): " << r.note << "\n";
    }
    for (const std::string& run : result.onlyA) out << "only in A: run " << run << "\n";
    for (const std::string& run : result.onlyB) out << "only in B: run " << run << "\n";
    auto list = [](const std::vector<std::string>& v) {
        std::string s;
        for (const std::string& x : v) s += (s.empty() ? "" : ", ") + x;
        return s;
    };
    if (!result.columnsOnlyA.empty()) out << "columns only in A (not compared): " << list(result.columnsOnlyA) << "\n";
    if (!result.columnsOnlyB.empty()) out << "columns only in B (not compared): " << list(result.columnsOnlyB) << "\n";
    out << result.regressions << " significantly slower beyond " << fixed(100 * options.threshold, 1) << "% (Mann-Whitney p < "
        << options.alpha << "), " << result.improvements << " faster, " << result.countDifferences << " count difference(s)\n";
}

}  // namespace rtbench
