#include "compare.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <map>
#include <set>
#include <sstream>

#include "columns.h"
#include "output_folder.h"
#include "config.h"
#include "statistics.h"
#include "core/error.h"
#include "methods/registry.h"
#include "timing_rounds.h"
#include "samples_check.h"
#include "writers.h"

namespace rtbench {
namespace fs = std::filesystem;

namespace {

// One side: its rows, its header and its samples by "run|config_hash|method".
struct Side {
    std::vector<Row> rows;
    std::set<std::string> columns;
    std::map<std::string, std::vector<double>> samples;
    int schema = kSchemaVersion;  // its results schema (context.json or runs.csv)
};

Side load(const std::string& folder) {
    std::error_code ec;
    if (!fs::is_directory(folder, ec)) throw Error(folder + ": not a results folder (no such folder)");
    refuseFolderBeingWritten(folder, "compare");
    const std::string csv = (fs::path(folder) / "runs.csv").string();
    if (!fs::exists(fs::symlink_status(csv, ec)))
        throw Error(csv + ": not found (not a results folder, or its shards are not merged yet)");
    Side side;
    int& schema = side.schema;
    side.rows = readRunsCsv(csv, &schema);
    if (!side.rows.empty())
        for (const auto& [column, value] : side.rows.front()) side.columns.insert(column);
    // The samples are the evidence a verdict rests on: from results schema 5 on, every ok row's
    // must be there and its own (samples_check.h), else the folder is refused.
    const std::string samples = (fs::path(folder) / "samples.csv").string();
    if (!fs::exists(fs::symlink_status(samples, ec))) {
        if (schema >= 5 && !side.rows.empty())
            throw Error(samples + ": missing; a folder of results schema " + std::to_string(schema) +
                        " keeps every timing sample there, and compare judges on them");
        return side;
    }
    const std::vector<Row> rows = readSamplesCsv(samples);
    const auto byRun = samplesByRun(rows);
    for (const Row& row : side.rows)
        if (const std::string problem = samplesProblem(row, byRun); !problem.empty())
            throw Error(samples + ": run " + cellText(row, "run") + " (" + cellText(row, "label") + "): " + problem +
                        "; its timings cannot be trusted");
    for (const Row& s : rows) side.samples[s.at("run") + "|" + s.at("config_hash") + "|" + s.at("method")].push_back(cellNumber(s.at("ms")));
    return side;
}

// A run's samples of one method; none when the folder (or the run) has none.
std::vector<double> timesOf(const Side& side, const Row& row, const std::string& method) {
    const auto it = side.samples.find(cellText(row, "run") + "|" + cellText(row, "config_hash") + "|" + method);
    if (it != side.samples.end()) return it->second;
    return {};
}

std::string percent(double fraction) {
    if (!std::isfinite(fraction)) return "-";
    std::ostringstream s;
    s << std::showpos << std::fixed << std::setprecision(1) << 100.0 * fraction << "%";
    return s.str();
}

// Config key columns, each with its key's name ("camera_position_x" -> "camera.position").
std::map<std::string, std::string> keyOfColumn() {
    std::map<std::string, std::string> keys;
    for (const KeySpec& k : configSchema())
        for (const std::string& c : keyColumns(k)) keys[c] = k.name;
    return keys;
}

// The columns that identify a run's work: its config keys both files have, in declared order, but
// not where the results went or how they were timed (experiment.*), the device (compare one config
// across devices) or a key given to --ignore.
std::vector<std::string> matchColumns(const Side& a, const Side& b, const CompareOptions& options) {
    const std::map<std::string, std::string> keys = keyOfColumn();
    std::set<std::string> ignored;
    for (const std::string& key : options.ignore) {
        keySpec(key);  // throws naming an unknown key
        ignored.insert(key);
    }
    std::vector<std::string> matchOn;
    for (const std::string& c : runColumns()) {
        const auto key = keys.find(c);
        if (key == keys.end() || c.rfind("experiment_", 0) == 0 || c.rfind("device_", 0) == 0) continue;
        if (!ignored.count(key->second) && a.columns.count(c) && b.columns.count(c)) matchOn.push_back(c);
    }
    return matchOn;
}

// Keys whose values differ between the folders: what keeps their runs from matching.
std::vector<std::string> differingKeys(const Side& a, const Side& b, const std::vector<std::string>& matchOn) {
    const std::map<std::string, std::string> keys = keyOfColumn();
    std::vector<std::string> differing;
    std::set<std::string> said;
    for (const std::string& c : matchOn) {
        std::set<std::string> inA, inB;
        for (const Row& row : a.rows) inA.insert(cellText(row, c));
        for (const Row& row : b.rows) inB.insert(cellText(row, c));
        if (inA == inB || said.count(keys.at(c))) continue;
        said.insert(keys.at(c));
        auto list = [](const std::set<std::string>& values) {
            std::string text;
            for (const std::string& v : values) text += (text.empty() ? "" : ", ") + (v.empty() ? "(none)" : v);
            return text;
        };
        differing.push_back(keys.at(c) + ": A " + list(inA) + "; B " + list(inB));
    }
    return differing;
}

// The samples a verdict is judged on: the kernel's, or with relativeTo = embree1 each divided by
// Embree's median on the same rays in the same folder. None when the run has no such samples.
std::vector<double> measured(const Side& side, const Row& row, const CompareOptions& options) {
    std::vector<double> kernel = timesOf(side, row, "kernel");
    if (options.relativeTo.empty() || kernel.empty()) return kernel;
    const std::vector<double> embree = timesOf(side, row, options.relativeTo);
    if (embree.empty()) return {};
    const double scale = median(embree);
    for (double& v : kernel) v /= scale;
    return kernel;
}

// Counts (exact columns both files have) that differ, status among them (ok -> failed).
std::vector<std::string> countDifferences(const Side& a, const Side& b, const Row& rowA, const Row& rowB) {
    std::vector<std::string> differences;
    for (const ColumnSpec& c : runColumnSpecs())
        if (c.kind == ColumnKind::Exact && c.name != "error" && c.name != "warnings" && a.columns.count(c.name) &&
            b.columns.count(c.name) && cellText(rowA, c.name) != cellText(rowB, c.name))
            differences.push_back(c.name + ": " + cellText(rowA, c.name) + " -> " + cellText(rowB, c.name));
    return differences;
}

// The change of measure the row's strategy declares (StrategyType::kernelMeasureChanges) between
// two schemas, if any; a key the row's schema did not have yet takes its default.
const MeasureChange* measureChangeBetween(int schemaA, int schemaB, const Row& row) {
    const StrategyType* type = findStrategyType(cellText(row, "strategy_type"));
    if (!type) return nullptr;
    auto valueOf = [&](const std::string& key) -> std::optional<std::string> {
        const std::string cell = cellText(row, paramColumn(key));
        if (!cell.empty()) return cell;
        const KeySpec& spec = keySpec(key);
        return spec.defaultValue ? std::optional<std::string>(formatValue(*spec.defaultValue)) : std::nullopt;
    };
    for (const MeasureChange& change : type->kernelMeasureChanges)
        if ((schemaA < change.schema) != (schemaB < change.schema) && conditionsHold(change.appliesWhen, valueOf))
            return &change;
    return nullptr;
}

// One matched pair, its verdict not yet given (that waits for the Holm correction over all).
ComparedRun compareRun(const Side& a, const Side& b, const Row& rowA, const Row& rowB, const CompareOptions& options) {
    ComparedRun run;
    run.key = cellText(rowA, "label");
    run.runA = cellText(rowA, "run");
    run.runB = cellText(rowB, "run");
    run.accuracyA = cellText(rowA, "exact_wrong_ppm");
    run.accuracyB = cellText(rowB, "exact_wrong_ppm");
    const bool okA = cellText(rowA, "status") == "ok", okB = cellText(rowB, "status") == "ok";
    if (okA != okB) run.countDifferences.push_back("status: " + cellText(rowA, "status") + " -> " + cellText(rowB, "status"));
    if (!okA || !okB) {
        run.failed = true;
        run.why = std::string(okA ? "" : "failed in A") + (!okA && !okB ? ", " : "") + (okB ? "" : "failed in B");
        return run;
    }
    run.countDifferences = countDifferences(a, b, rowA, rowB);
    // The measure: the samples when both folders have them, else the rows' medians (no test).
    const std::vector<double> sampleA = measured(a, rowA, options), sampleB = measured(b, rowB, options);
    auto rowMedian = [&](const Row& row) {
        const double kernel = cellNumber(cellText(row, "kernel_ms_median"));
        return options.relativeTo.empty() ? kernel : kernel / cellNumber(cellText(row, options.relativeTo + "_ms_median"));
    };
    const bool sampled = !sampleA.empty() && !sampleB.empty();
    run.medianA = sampled ? median(sampleA) : rowMedian(rowA);
    run.medianB = sampled ? median(sampleB) : rowMedian(rowB);
    run.change = run.medianB / run.medianA - 1.0;
    const std::vector<double> embreeA = timesOf(a, rowA, "embree1"), embreeB = timesOf(b, rowB, "embree1");
    const double embreeMedianA = !embreeA.empty() ? median(embreeA) : cellNumber(cellText(rowA, "embree1_ms_median"));
    const double embreeMedianB = !embreeB.empty() ? median(embreeB) : cellNumber(cellText(rowB, "embree1_ms_median"));
    run.embreeChange = embreeMedianB / embreeMedianA - 1.0;
    run.changeLow = run.changeHigh = std::nan("");
    if (sampled) {
        if (const std::optional<Interval> ratio = ratioOfMediansInterval(sampleB, sampleA)) {
            run.changeLow = ratio->low - 1.0;
            run.changeHigh = ratio->high - 1.0;
        }
        run.p = mannWhitneyU(sampleB, sampleA).p;
    } else {
        run.why = std::string("no samples of this run in ") +
                  (sampleA.empty() && sampleB.empty() ? "A and B" : sampleA.empty() ? "A" : "B") + ": medians only, no test";
    }
    run.flagged = !cellText(rowA, "timing_warning").empty() || !cellText(rowB, "timing_warning").empty();
    if (run.flagged)
        run.why = std::string("timing warning in ") +
                  (cellText(rowA, "timing_warning").empty() ? "B" : cellText(rowB, "timing_warning").empty() ? "A" : "A and B");
    // A strategy whose kernel_ms became another measure between the two folders' schemas.
    if (const MeasureChange* change = measureChangeBetween(a.schema, b.schema, rowA)) {
        run.flagged = true;
        run.why = change->what + " (A: schema " + std::to_string(a.schema) + ", B: " + std::to_string(b.schema) +
                  "): not the same measure";
    }
    return run;
}

// Holm's step-down correction over the runs tested: the k-th smallest of m p-values times
// (m - k + 1), kept from falling below the one before it, at most 1.
void holm(std::vector<ComparedRun>& runs) {
    std::vector<ComparedRun*> tested;
    for (ComparedRun& r : runs)
        if (r.p >= 0) tested.push_back(&r);
    std::stable_sort(tested.begin(), tested.end(), [](const ComparedRun* x, const ComparedRun* y) { return x->p < y->p; });
    double floor = 0.0;
    for (std::size_t k = 0; k < tested.size(); ++k) {
        floor = std::max(floor, std::min(1.0, double(tested.size() - k) * tested[k]->p));
        tested[k]->pHolm = floor;
    }
}

// SLOWER or FASTER: a Holm-corrected p below alpha and a change beyond the threshold; SAME: a
// change within it (significant or not); UNSURE: a timing warning, no samples, a failed side, or
// a change beyond the threshold that the samples cannot tell from noise.
void judge(ComparedRun& run, const CompareOptions& options) {
    if (run.failed || run.flagged || run.p < 0) {
        run.verdict = Verdict::Unsure;
        return;
    }
    const bool beyond = std::abs(run.change) > options.threshold;
    if (run.pHolm < options.alpha && beyond) {
        run.verdict = run.change > 0 ? Verdict::Slower : Verdict::Faster;
        run.why = "Holm p < " + formatNumber(options.alpha, 3) + ", change beyond " + percent(options.threshold).substr(1);
    } else if (!beyond) {
        run.verdict = Verdict::Same;
        run.why = "change within " + percent(options.threshold).substr(1);
    } else {
        run.verdict = Verdict::Unsure;
        run.why = "change beyond " + percent(options.threshold).substr(1) + " but Holm p = " + formatNumber(run.pHolm, 3);
    }
}

}  // namespace

const char* verdictName(Verdict verdict) {
    switch (verdict) {
        case Verdict::Same:
            return "SAME";
        case Verdict::Faster:
            return "FASTER";
        case Verdict::Slower:
            return "SLOWER";
        case Verdict::Unsure:
            return "UNSURE";
    }
    return "?";
}

CompareResult compareFolders(const std::string& folderA, const std::string& folderB, const CompareOptions& options) {
    if (!(options.threshold >= 0) || !(options.alpha > 0 && options.alpha <= 1))
        throw Error("compare: --threshold must be >= 0 and --alpha in (0, 1]");
    if (!options.relativeTo.empty() && options.relativeTo != "embree1")
        throw Error("compare: --relative-to '" + options.relativeTo + "': the one measure to judge against is embree1");
    const Side a = load(folderA), b = load(folderB);
    CompareResult result;
    for (const std::string& c : a.columns)
        if (!b.columns.count(c)) result.columnsOnlyA.push_back(c);
    for (const std::string& c : b.columns)
        if (!a.columns.count(c)) result.columnsOnlyB.push_back(c);
    const std::vector<std::string> matchOn = matchColumns(a, b, options);
    auto keyOf = [&](const Row& row) {
        std::string key;
        for (const std::string& c : matchOn) key += c + "=" + cellText(row, c) + ";";
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
            result.onlyA.push_back(cellText(rowA, "run") + " (" + cellText(rowA, "label") + ")");
            continue;
        }
        matchedB.insert(candidates->second[k]);
        result.runs.push_back(compareRun(a, b, rowA, *candidates->second[k], options));
    }
    for (const Row& row : b.rows)
        if (!matchedB.count(&row)) result.onlyB.push_back(cellText(row, "run") + " (" + cellText(row, "label") + ")");
    if (!result.onlyA.empty() || !result.onlyB.empty()) result.differingKeys = differingKeys(a, b, matchOn);
    holm(result.runs);
    for (ComparedRun& run : result.runs) {
        judge(run, options);
        result.countDifferences += int(run.countDifferences.size());
        result.same += run.verdict == Verdict::Same;
        result.faster += run.verdict == Verdict::Faster;
        result.slower += run.verdict == Verdict::Slower;
        result.unsure += run.verdict == Verdict::Unsure;
    }
    return result;
}

namespace {

std::string fixed(double v, int digits) {
    if (!std::isfinite(v)) return "-";
    std::ostringstream s;
    s << std::fixed << std::setprecision(digits) << v;
    return s.str();
}

std::string joined(const std::vector<std::string>& values) {
    std::string text;
    for (const std::string& v : values) text += (text.empty() ? "" : ", ") + v;
    return text;
}

std::string measureName(const CompareOptions& options) {
    return options.relativeTo.empty() ? "kernel ms" : "kernel ms / " + options.relativeTo + " ms";
}

// The table: aligned text, or Markdown.
void printTable(const CompareResult& result, const CompareOptions& options, std::ostream& out) {
    const std::string measure = measureName(options);
    const std::vector<std::string> header = {"A", "B", "parameters", measure + " A", measure + " B", "change", "95% interval",
                                             "p (Holm)", "Embree1 change", "wrong ppm A / B", "verdict"};
    std::vector<std::vector<std::string>> table;
    for (const ComparedRun& r : result.runs) {
        const int digits = options.relativeTo.empty() ? 4 : 3;
        table.push_back({r.runA, r.runB, r.key, r.failed ? "-" : fixed(r.medianA, digits),
                         r.failed ? "-" : fixed(r.medianB, digits), r.failed ? "-" : percent(r.change),
                         std::isfinite(r.changeLow) && !r.failed ? "[" + percent(r.changeLow) + ", " + percent(r.changeHigh) + "]" : "-",
                         r.pHolm < 0 ? "-" : fixed(r.pHolm, 4), r.failed ? "-" : percent(r.embreeChange),
                         (r.accuracyA.empty() ? "-" : r.accuracyA) + " / " + (r.accuracyB.empty() ? "-" : r.accuracyB),
                         verdictName(r.verdict)});
    }
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
        return;
    }
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

Json runJson(const ComparedRun& r) {
    auto number = [](double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); };
    Json differences = Json::array();
    for (const std::string& d : r.countDifferences) differences.push_back(d);
    return Json{{"run_a", r.runA},
                {"run_b", r.runB},
                {"parameters", r.key},
                {"median_a", r.failed ? Json(nullptr) : number(r.medianA)},
                {"median_b", r.failed ? Json(nullptr) : number(r.medianB)},
                {"change", r.failed ? Json(nullptr) : number(r.change)},
                {"change_low", number(r.changeLow)},
                {"change_high", number(r.changeHigh)},
                {"p", r.p < 0 ? Json(nullptr) : Json(r.p)},
                {"p_holm", r.pHolm < 0 ? Json(nullptr) : Json(r.pHolm)},
                {"embree1_change", r.failed ? Json(nullptr) : number(r.embreeChange)},
                {"wrong_ppm_a", r.accuracyA},
                {"wrong_ppm_b", r.accuracyB},
                {"verdict", verdictName(r.verdict)},
                {"why", r.why},
                {"count_differences", differences}};
}

// docs/commands.md (compare --json) documents this document's fields.
void printJson(const CompareResult& result, const std::string& folderA, const std::string& folderB,
               const CompareOptions& options, std::ostream& out) {
    Json runs = Json::array();
    for (const ComparedRun& r : result.runs) runs.push_back(runJson(r));
    const Json document{{"schema", 1},
                        {"a", folderA},
                        {"b", folderB},
                        {"measure", measureName(options)},
                        {"threshold", options.threshold},
                        {"alpha", options.alpha},
                        {"runs", runs},
                        {"only_a", result.onlyA},
                        {"only_b", result.onlyB},
                        {"differing_keys", result.differingKeys},
                        {"summary", Json{{"same", result.same}, {"faster", result.faster}, {"slower", result.slower},
                                         {"unsure", result.unsure}, {"count_differences", result.countDifferences}}},
                        {"exit", result.exitStatus()}};
    out << document.dump(2, ' ', false, Json::error_handler_t::replace) << "\n";
}

}  // namespace

void printComparison(const CompareResult& result, const std::string& folderA, const std::string& folderB,
                     const CompareOptions& options, std::ostream& out) {
    if (options.json) return printJson(result, folderA, folderB, options, out);
    out << "rtbench compare " << folderA << " (A) -> " << folderB << " (B): " << result.runs.size()
        << " runs matched by their parameters";
    if (!result.onlyA.empty() || !result.onlyB.empty())
        out << " (" << result.onlyA.size() << " only in A, " << result.onlyB.size() << " only in B)";
    out << "; judged on " << measureName(options) << "\n";
    if (!result.runs.empty()) printTable(result, options, out);
    for (const ComparedRun& r : result.runs) {
        for (const std::string& d : r.countDifferences)
            out << "count differs: run " << r.runA << " -> " << r.runB << " (" << r.key << "): " << d << "\n";
        if (r.verdict == Verdict::Unsure && !r.why.empty()) out << "unsure: run " << r.runA << " (" << r.key << "): " << r.why << "\n";
    }
    for (const std::string& run : result.onlyA) out << "only in A: run " << run << "\n";
    for (const std::string& run : result.onlyB) out << "only in B: run " << run << "\n";
    for (const std::string& key : result.differingKeys) out << "differs between the folders: " << key << "\n";
    if (!result.columnsOnlyA.empty()) out << "columns only in A (not compared): " << joined(result.columnsOnlyA) << "\n";
    if (!result.columnsOnlyB.empty()) out << "columns only in B (not compared): " << joined(result.columnsOnlyB) << "\n";
    if (result.runs.empty()) {
        out << "no run matched: nothing compared" << (result.differingKeys.empty() ? "" : " (--ignore KEY matches runs across a key)")
            << "\n";
        return;
    }
    out << result.same << " SAME, " << result.faster << " FASTER, " << result.slower << " SLOWER, " << result.unsure
        << " UNSURE (beyond " << fixed(100 * options.threshold, 1) << "% with a Mann-Whitney p < " << options.alpha
        << " after Holm's correction for " << result.runs.size() << " runs), " << result.countDifferences
        << " count difference(s)\n";
}

}  // namespace rtbench
