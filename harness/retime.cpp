#include "retime.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include "check.h"
#include "columns.h"
#include "schema/column.h"
#include "output_folder.h"
#include "samples_check.h"
#include "statistics.h"
#include "runner.h"
#include "timing_rounds.h"
#include "version.h"
#include "core/error.h"
#include "writers.h"

namespace rtbench {
namespace fs = std::filesystem;

const Column<std::string>& retimedColumn() {
    static const Column<std::string> column(
        {"retimed", ColumnKind::Context, "",
         "rtbench retime: when the run was re-timed, which try's timings were kept and why (no timing warning beats one, then the "
         "narrower widest spread: a median's interval half-width, or below 6 repetitions the CV), or that none was better "
         "conditioned; empty when never re-timed", 0.0, false, {}, 24});
    return column;
}

namespace {

// How well a run's timings are conditioned: no timing warning beats one, then the narrower widest
// spread of its methods (kernel, Embree 1, Embree 16) as the noise guard judges it: the median's
// interval half-width over the median, or below 6 repetitions the CV (harness/noise_guard.h).
struct Conditioning {
    bool warned = true;
    double largestSpread = std::numeric_limits<double>::infinity();
    bool betterThan(const Conditioning& other) const {
        return warned != other.warned ? !warned : largestSpread < other.largestSpread;
    }
    std::string text() const {
        std::ostringstream s;
        s << "widest spread ";
        if (std::isfinite(largestSpread)) s << "+-" << formatNumber(100.0 * largestSpread, 3) << "%";
        else s << "unknown";
        return s.str();
    }
};

// One method's spread from its columns: the interval where the row has one, else the CV.
double spreadOf(const Row& row, const std::string& method) {
    const double low = cellNumber(cellText(row, method + "_ms_ci_low")), high = cellNumber(cellText(row, method + "_ms_ci_high"));
    const double median = cellNumber(cellText(row, method + "_ms_median"));
    if (std::isfinite(low) && std::isfinite(high) && median > 0) return relativeHalfWidth(Interval{low, high}, median);
    return cellNumber(cellText(row, method + "_ms_cv"));
}

Conditioning conditioning(const Row& row) {
    Conditioning c;
    c.warned = !cellText(row, "timing_warning").empty();
    double largest = -1.0;
    for (const char* method : {"kernel", "embree1", "embree16"}) {
        const double spread = spreadOf(row, method);
        if (std::isfinite(spread)) largest = std::max(largest, spread);
    }
    if (largest >= 0.0) c.largestSpread = largest;
    return c;
}

// The best try of one flagged run so far.
struct Best {
    Row row;
    std::vector<Row> samples;
    int attempt = 0;  // 0: the record
    Conditioning conditioning;
};

// Each flagged run must have been timed by this binary on this CPU: a re-time by another commit or
// machine would mix two identities in one folder.
void requireSameIdentity(const std::vector<const Row*>& flagged, const std::string& csvPath) {
    const std::string commit = gitCommit(), cpu = cpuModel();
    for (const Row* row : flagged)
        if (cellText(*row, "git_commit") != commit || cellText(*row, "cpu") != cpu)
            throw Error(csvPath + ": run " + cellText(*row, "run") + " was timed by commit " + cellText(*row, "git_commit") +
                        " on \"" + cellText(*row, "cpu") + "\"; this binary is commit " + commit + " on \"" + cpu +
                        "\": re-time with the binary and machine that recorded it, or re-run the config");
}

// One try: the runs still flagged, re-run together into a scratch folder; returns the rows and samples.
std::pair<std::vector<Row>, std::vector<Row>> reRun(const ExperimentPlan& plan, const std::set<std::string>& runs) {
    RunnerOptions runner;
    runner.quiet = true;
    runner.force = true;
    runner.onlyRuns = runs;
    const ScratchFolder scratch("rtbench-retime");
    runner.outputOverride = scratch.path();
    ExperimentResult now = runExperiment(plan, runner);
    std::vector<Row> samples = readSamplesCsv((fs::path(now.folder) / samplesFileName(runner)).string());
    return {std::move(now.rows), std::move(samples)};
}

// What a try of a recorded run did: the deterministic differences (a failure), else whether it
// is the best so far.
void judgeTry(const Row& recorded, const Row& fresh, const std::vector<Row>& freshSamples, int attempt, Best& best,
              std::vector<std::string>& differences, std::ostream& out) {
    std::vector<std::string> found = deterministicDifferences(recorded, fresh);
    for (const char* column : {"device", "driver", "cpu", "git_commit"})
        if (cellText(recorded, column) != cellText(fresh, column))
            found.push_back(cellText(recorded, "run") + " " + column + " " + cellText(recorded, column) + " -> " +
                            cellText(fresh, column));
    if (cellText(fresh, "status") != "ok")
        found.push_back(cellText(recorded, "run") + " status ok -> " + cellText(fresh, "status") + ": " +
                        cellText(fresh, "error"));
    if (!found.empty()) {
        differences.insert(differences.end(), found.begin(), found.end());
        return;
    }
    const Conditioning c = conditioning(fresh);
    out << "  run " << cellText(recorded, "run") << " try " << attempt << ": " << c.text()
        << (c.warned ? " [" + cellText(fresh, "timing_warning") + "]" : ", no timing warning") << "\n";
    if (!c.betterThan(best.conditioning)) return;
    best.row = fresh;
    best.attempt = attempt;
    best.conditioning = c;
    best.samples.clear();
    for (const Row& s : freshSamples)
        if (runKey(s) == runKey(fresh)) best.samples.push_back(s);
}

// The `retimed` cell of a flagged run after its tries.
std::string retimedNote(const Row& recorded, const Best& best, int tries, const std::string& when) {
    const Conditioning before = conditioning(recorded);
    if (best.attempt == 0)
        return when + ": " + std::to_string(tries) + " tries, none better conditioned than the record (" + before.text() +
               "); the recorded timings kept";
    return when + ": try " + std::to_string(best.attempt) + " of " + std::to_string(tries) + " kept (" +
           (best.conditioning.warned ? "still a timing warning" : "timing warning cleared") + "; " + before.text() +
           " -> " + best.conditioning.text() + "); the record's warning was: " + cellText(recorded, "timing_warning");
}

// samples.csv with each replaced run's samples swapped for its kept try's, where they stood.
std::vector<Row> replaceSamples(const std::vector<Row>& samples, const std::map<std::string, Best>& best) {
    std::vector<Row> out;
    std::set<std::string> placed;
    for (const Row& s : samples) {
        const auto it = best.find(runKey(s));
        if (it == best.end() || it->second.attempt == 0) {
            out.push_back(s);
        } else if (placed.insert(it->first).second) {
            out.insert(out.end(), it->second.samples.begin(), it->second.samples.end());
        }
    }
    return out;
}

// Writes the folder: the replaced rows and samples aside first (so nothing is lost whatever
// happens after), then samples.csv, runs.csv and a line of history in context.json.
void writeRetimed(const FolderIdentity& folder, std::vector<Row> rows, const std::vector<Row>& samples,
                  const std::map<std::string, Best>& best, Json context, const RetimeOptions& options, const std::string& when) {
    std::vector<Row> asideRows, asideSamples;
    std::vector<std::string> replacedRuns;
    for (Row& row : rows) {
        const auto it = best.find(runKey(row));
        if (it == best.end()) continue;
        if (it->second.attempt > 0) {
            asideRows.push_back(row);
            replacedRuns.push_back(cellText(row, "run"));
        }
        const std::string note = retimedNote(row, it->second, options.tries, when);
        if (it->second.attempt > 0) row = it->second.row;
        put(row, retimedColumn(), note);
    }
    for (const Row& s : samples)
        if (const auto it = best.find(runKey(s)); it != best.end() && it->second.attempt > 0) asideSamples.push_back(s);
    const fs::path dir = folder.path();
    folder.check();
    if (!asideRows.empty()) {
        const std::string prefix = supersededPrefix(dir.string());
        writeCsv(prefix + "runs.csv", runColumns(), asideRows);
        writeCsv(prefix + "samples.csv", sampleColumns(), asideSamples);
    }
    folder.check();
    writeCsv((dir / "samples.csv").string(), sampleColumns(), replaceSamples(samples, best));
    writeCsv((dir / "runs.csv").string(), runColumns(), rows);
    context["retimed"].push_back(Json{{"time", when}, {"tries", options.tries}, {"runs_replaced", replacedRuns},
                                      {"runs_flagged", best.size()}});
    writeJson((dir / "context.json").string(), context);
}

}  // namespace

RetimeResult retimeFlagged(const std::string& folderPath, const RetimeOptions& options, std::ostream& out) {
    if (options.tries < 1 || options.tries > 100)
        throw Error("--tries " + std::to_string(options.tries) + ": expected 1 to 100");
    refuseSymlinks(folderPath);
    const OutputFolderLock lock(folderPath);
    const FolderIdentity folder(folderPath);
    const std::string contextPath = (fs::path(folderPath) / "context.json").string();
    const std::string csvPath = (fs::path(folderPath) / "runs.csv").string();
    if (!fs::exists(contextPath)) throw Error(contextPath + ": not found (is this a results folder?)");
    const Json context = readJson(contextPath);
    const ExperimentPlan plan = recordedPlan(context, contextPath);
    int schema = kSchemaVersion;
    const std::vector<Row> rows = readRunsCsv(csvPath, &schema);
    if (schema < kSchemaVersion)
        throw Error(csvPath + ": results schema " + std::to_string(schema) + ", this binary writes " +
                    std::to_string(kSchemaVersion) + ": re-run the config (a re-time would mix two schemas' timings)");
    const std::vector<Row> samples = readSamplesCsv((fs::path(folderPath) / "samples.csv").string());

    std::vector<const Row*> flagged;
    for (const Row& row : rows)
        if (cellText(row, "status") == "ok" && !cellText(row, "timing_warning").empty()) flagged.push_back(&row);
    RetimeResult result;
    result.flagged = int(flagged.size());
    out << "rtbench retime " << folderPath << ": " << flagged.size() << " of " << rows.size()
        << " runs have a timing warning" << (flagged.empty() ? "; nothing to re-time\n" : "\n");
    if (flagged.empty()) return result;
    requireSameIdentity(flagged, csvPath);

    std::map<std::string, Best> best;
    std::map<std::string, const Row*> recordOf;  // flagged runs by run|config_hash
    for (const Row* row : flagged) {
        best[runKey(*row)].conditioning = conditioning(*row);
        recordOf[runKey(*row)] = row;
    }
    for (int attempt = 1; attempt <= options.tries; ++attempt) {
        std::set<std::string> still;  // runs without a clean try yet
        for (const auto& [key, row] : recordOf)
            if (best[key].conditioning.warned) still.insert(cellText(*row, "run"));
        if (still.empty()) break;
        out << "try " << attempt << " of " << options.tries << ": re-timing " << still.size() << " run(s)\n";
        const auto [fresh, freshSamples] = reRun(plan, still);
        for (const Row& row : fresh)
            if (const auto it = recordOf.find(runKey(row)); it != recordOf.end())
                judgeTry(*it->second, row, freshSamples, attempt, best[it->first], result.differences, out);
        if (!result.differences.empty()) return result;  // a count moved: nothing is written
    }
    for (const auto& [key, b] : best) {
        result.replaced += b.attempt > 0;
        result.cleared += b.attempt > 0 && !b.conditioning.warned;
    }
    writeRetimed(folder, rows, samples, best, context, options, utcNow());
    out << result.replaced << " run(s) re-timed with better-conditioned samples (" << result.cleared
        << " now without a timing warning), " << result.flagged - result.replaced
        << " kept as recorded; the replaced rows and samples are in superseded-*-runs.csv and -samples.csv\n";
    return result;
}

}  // namespace rtbench
