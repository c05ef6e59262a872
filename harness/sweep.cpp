#include "sweep.h"

#include <algorithm>
#include <chrono>
#include <iomanip>
#include <iostream>
#include <memory>

#include "harness/interrupt_note.h"
#include "harness/plan_view.h"
#include "harness/run_pipeline.h"
#include "harness/samples_check.h"
#include "harness/writers.h"
#include "run_columns.h"

namespace rtbench {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// samples.csv rows of one run as the timing samples they were (an interrupted sweep's rounds).
std::vector<TimingSample> timingSamples(const std::vector<Row>& rows) {
    std::vector<TimingSample> samples;
    for (const Row& r : rows)
        samples.push_back({r.at("method"), std::stoi(r.at("round")), std::stoi(r.at("repetition")), cellNumber(r.at("ms")),
                           cellNumber(r.at("t_s"))});
    std::stable_sort(samples.begin(), samples.end(), [](const TimingSample& a, const TimingSample& b) { return a.round < b.round; });
    return samples;
}

// A run's timing samples as samples.csv rows.
std::vector<Row> sampleRows(const Row& row, const std::vector<TimingSample>& samples) {
    std::vector<Row> rows;
    for (const TimingSample& s : samples)
        rows.push_back({{"run", row.at("run")}, {"config_hash", row.at("config_hash")}, {"method", s.method},
                        {"round", std::to_string(s.round)}, {"repetition", std::to_string(s.repetition)},
                        {"ms", formatNumber(s.ms, 9)}, {"t_s", formatNumber(s.t, 9)}});
    return rows;
}

// Records each run's row as it ends and says how the sweep goes: runs done, elapsed, an estimate
// of the time left.
class Recorder {
public:
    explicit Recorder(Sweep& s) : s_(s), rows_(s.resumed.rows), tookBefore_(s.mine.size(), -1.0) {
        rowsWritten_ = int(std::count(s.resumed.kept.begin(), s.resumed.kept.end(), true));
        if (!s.options.commandLine.empty())  // a sweep the user started (not check's re-run into a folder of its own)
            setInterruptNote(interruptNote(rowsWritten_, int(s.mine.size()), s.files.csvPath, s.options.commandLine));
        // The time left: an earlier row's wall_s for each run still to run that has one (a --force
        // re-run, another commit), the mean of the runs run so far for the others.
        const std::map<std::string, double> earlierWall = earlierWallSeconds(s.resumed.earlierRows);
        for (std::size_t k = 0; k < s.mine.size(); ++k) {
            const auto it = earlierWall.find(runKey(rows_[k]));
            if (it != earlierWall.end()) tookBefore_[k] = it->second;
        }
    }
    Row& row(std::size_t k) { return rows_[k]; }
    double elapsed() const { return since(start_); }
    // A run's row is complete (ok, or failed with `error`): said on the console, then its samples
    // and its row appended. The samples come first: an interrupt between them leaves samples
    // without a row, which a resume sets aside, never a row without its samples.
    void record(std::size_t k, const std::string& error, double seconds, const std::vector<TimingSample>& samples) {
        Row& row = rows_[k];
        const RunColumns& c = runColumnsDeclared();
        put(row, c.status, std::string(error.empty() ? "ok" : "failed"));
        if (!error.empty()) {
            put(row, c.error, error);
            ++s_.result.failed;
        }
        executedSeconds_ += seconds;
        ++executed_;
        put(row, c.wallSeconds, seconds);
        say(row);
        s_.folder.check();  // the folder opened, not one put in its place since
        appendCsvRows(s_.files.samplesPath, sampleColumns(), sampleRows(row, samples));
        appendCsvRow(s_.files.csvPath, s_.files.columns, row);  // an interrupt loses nothing done
        ++rowsWritten_;
        if (!s_.options.commandLine.empty())
            setInterruptNote(interruptNote(rowsWritten_, int(s_.mine.size()), s_.files.csvPath, s_.options.commandLine));
    }
    // Appends samples of a run still being timed (an interleaved round's).
    void appendSamples(std::size_t k, const std::vector<TimingSample>& samples) {
        s_.folder.check();
        appendCsvRows(s_.files.samplesPath, sampleColumns(), sampleRows(rows_[k], samples));
    }
    void progress(const char* what, std::size_t k) const {
        if (s_.options.quiet) return;
        std::cout << "[" << what << " " << k + 1 << "/" << s_.mine.size() << ", " << std::fixed << std::setprecision(0)
                  << elapsed() << " s";
        const double left = std::string(what) == "run" ? secondsLeft(k) : -1.0;
        if (left >= 0.0) std::cout << ", ~" << left << " s left";
        std::cout << "] " << s_.mine[k]->label() << " ..." << std::defaultfloat << std::flush;
    }

private:
    void say(const Row& row) {
        const RunnerOptions& o = s_.options;
        if (!o.quiet) {
            if (cellText(row, "status") == "ok")
                std::cout << " " << consoleNumber(cellText(row, "kernel_mrays_s")) << " Mrays/s (Embree "
                          << consoleNumber(cellText(row, "embree1_mrays_s")) << "), hit/miss agreement "
                          << cellText(row, "hit_miss_agreement") << ", " << consoleNumber(cellText(row, "wall_s")) << " s\n";
            else
                std::cout << " FAILED: " << cellText(row, "error") << "\n";
        }
        const std::string warnings = cellText(row, "warnings"), timing = cellText(row, "timing_warning");
        s_.result.warned += !warnings.empty() || !timing.empty();
        if (!warnings.empty() && !o.quiet) std::cerr << "[rtbench] run " << row.at("run") << " warning: " << warnings << "\n";
        if (!timing.empty() && !o.quiet)
            std::cerr << "[rtbench] run " << row.at("run") << " timing warning: " << timing << " (not a timing of record)\n";
    }
    double secondsLeft(std::size_t from) const {
        double known = 0.0;
        std::size_t unknown = 0;
        for (std::size_t j = from; j < s_.mine.size(); ++j) {
            if (s_.resumed.kept[j]) continue;
            if (tookBefore_[j] >= 0.0) known += tookBefore_[j];
            else ++unknown;
        }
        if (unknown == 0) return known;
        return executed_ > 0 ? known + executedSeconds_ / executed_ * double(unknown) : -1.0;
    }
    Sweep& s_;
    std::vector<Row>& rows_;
    std::vector<double> tookBefore_;  // each run's earlier wall_s, -1 where none
    Clock::time_point start_ = Clock::now();
    double executedSeconds_ = 0.0;
    int executed_ = 0, rowsWritten_ = 0;
};

void runSequential(Sweep& s, Recorder& recorder) {
    for (std::size_t k = 0; k < s.mine.size(); ++k) {
        if (s.resumed.kept[k]) continue;
        recorder.progress("run", k);
        const auto start = Clock::now();
        std::vector<TimingSample> samples;
        std::string error;
        try {
            executeRun(s.plan, *s.mine[k], s.folder, s.caches, recorder.row(k), samples);
        } catch (const std::exception& e) {
            error = failureReason(e);
        }
        recorder.record(k, error, since(start), samples);
    }
}

// Interleaved: the runs of the sweep, prepared (each keeps its device buffers until finished), and
// for each its seconds so far and its samples already in the file.
struct Interleaved {
    std::vector<std::unique_ptr<RunInProgress>> running;
    std::vector<double> seconds;
    std::vector<std::size_t> appended;
};

// Every run prepared (its instrumented run and checks); a run a killed sweep had timed goes on from
// the rounds it finished.
void prepareAll(Sweep& s, Recorder& recorder, Interleaved& in) {
    for (std::size_t k = 0; k < s.mine.size(); ++k) {
        if (s.resumed.kept[k]) continue;
        recorder.progress("prepare", k);
        const auto start = Clock::now();
        try {
            Row& row = recorder.row(k);
            in.running[k] = prepareRun(s.plan, *s.mine[k], s.caches, row);
            const auto resumed = s.resumed.rounds.find(runKey(row));
            if (resumed != s.resumed.rounds.end()) {
                in.running[k]->rounds->resume(timingSamples(resumed->second));
                in.appended[k] = resumed->second.size();
                if (!s.options.quiet)
                    std::cout << " prepared; " << in.running[k]->rounds->result().rounds << " round(s) kept from the interrupted sweep\n";
            } else if (!s.options.quiet) {
                std::cout << " prepared\n";
            }
        } catch (const std::exception& e) {
            recorder.record(k, failureReason(e), since(start), {});
        }
        in.seconds[k] += since(start);
    }
}

// Round after round across the sweep, each round's samples appended as it ends.
void timeInterleavedRounds(Sweep& s, Recorder& recorder, Interleaved& in) {
    for (int round = 0;; ++round) {
        std::size_t timing = 0;
        for (std::size_t k = 0; k < s.mine.size(); ++k) {
            if (!in.running[k] || in.running[k]->rounds->done()) continue;
            ++timing;
            const auto start = Clock::now();
            try {
                in.running[k]->rounds->runRound();
                const std::vector<TimingSample>& taken = in.running[k]->rounds->result().samples;
                recorder.appendSamples(k, std::vector<TimingSample>(taken.begin() + in.appended[k], taken.end()));
                in.appended[k] = taken.size();
            } catch (const std::exception& e) {
                in.running[k].reset();  // its buffers go now
                if (!s.options.quiet) std::cout << "[round " << round + 1 << "] " << s.mine[k]->label() << ":";
                recorder.record(k, failureReason(e), in.seconds[k] + since(start), {});
            }
            in.seconds[k] += since(start);
        }
        if (!timing) break;
        if (!s.options.quiet)
            std::cout << "[round " << round + 1 << ", " << std::fixed << std::setprecision(0) << recorder.elapsed() << " s] "
                      << timing << " run(s) timed\n" << std::defaultfloat;
    }
}

void finishAll(Sweep& s, Recorder& recorder, Interleaved& in) {
    for (std::size_t k = 0; k < s.mine.size(); ++k) {
        if (!in.running[k]) continue;
        recorder.progress("finish", k);
        const auto start = Clock::now();
        std::vector<TimingSample> samples;
        std::string error;
        try {
            finishRun(*in.running[k], s.folder, s.caches, recorder.row(k), samples);
        } catch (const std::exception& e) {
            error = failureReason(e);
        }
        in.running[k].reset();
        // Its rounds' samples are in the file already: the row and any samples after them.
        recorder.record(k, error, in.seconds[k] + since(start),
                        std::vector<TimingSample>(samples.begin() + std::min(in.appended[k], samples.size()), samples.end()));
    }
}

}  // namespace

void runSweep(Sweep& s) {
    Recorder recorder(s);
    for (std::size_t k = 0; k < s.mine.size(); ++k)
        if (s.resumed.kept[k]) {
            ++s.result.reused;
            if (!s.options.quiet)
                std::cout << "[run " << k + 1 << "/" << s.mine.size() << "] " << s.mine[k]->label() << ": done before, kept\n";
        }
    if (s.plan.runs.front().getString("experiment.order") != "interleaved") return runSequential(s, recorder);
    Interleaved in{std::vector<std::unique_ptr<RunInProgress>>(s.mine.size()), std::vector<double>(s.mine.size(), 0.0),
                   std::vector<std::size_t>(s.mine.size(), 0)};
    prepareAll(s, recorder, in);
    timeInterleavedRounds(s, recorder, in);
    finishAll(s, recorder, in);
}

}  // namespace rtbench
