// `rtbench merge`: the shards of a sharded sweep (runs.shard-<i>-of-<n>.csv) joined into runs.csv
// (shard_merge.h).
#include "shard_merge.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>

#include "check.h"
#include "output_folder.h"
#include "columns.h"
#include "run_columns.h"
#include "runner.h"
#include "timing_rounds.h"
#include "core/error.h"
#include "core/text.h"

namespace rtbench {
namespace fs = std::filesystem;

namespace {

// One shard's files as merge reads them.
struct ShardFiles {
    fs::path csv, context;
    Json json;
};

std::string contextField(const Json& context, const fs::path& path, const char* key) {
    const auto it = context.find(key);
    if (it == context.end() && std::string(key) == "settings") return "[]";  // written only when --set was given
    if (it == context.end()) throw Error(path.string() + ": no \"" + key + "\" field");
    return it->is_string() ? it->get<std::string>() : it->dump();
}

// runs.shard-<i>-of-<n>.csv with its context.shard-<i>-of-<n>.json, every one, of one split.
std::map<std::string, ShardFiles> findShards(const std::string& folder) {
    std::map<std::string, ShardFiles> shards;
    const std::regex csvName(R"(runs\.(shard-[0-9]+-of-[0-9]+)\.csv)"), contextName(R"(context\.(shard-[0-9]+-of-[0-9]+)\.json)");
    for (const auto& entry : fs::directory_iterator(folder)) {
        const std::string name = entry.path().filename().string();
        std::smatch m;
        if (std::regex_match(name, m, csvName)) shards[m[1]].csv = entry.path();
        if (std::regex_match(name, m, contextName)) shards[m[1]].context = entry.path();
    }
    if (shards.empty()) throw Error(folder + ": no runs.shard-*.csv files to merge");
    std::set<std::string> counts;
    for (auto& [shard, files] : shards) {
        if (files.csv.empty()) throw Error(folder + ": " + files.context.filename().string() + " has no runs." + shard + ".csv");
        if (files.context.empty()) throw Error(folder + ": " + files.csv.filename().string() + " has no context." + shard + ".json");
        files.json = readJson(files.context.string());
        counts.insert(shard.substr(shard.rfind("-of-") + 4));
    }
    if (counts.size() > 1) throw Error(folder + ": shards of different splits (of-" + *counts.begin() + " and of-" + *counts.rbegin() + ")");
    return shards;
}

// The shards must be parts of one experiment: the same config text, overrides, plan and commit.
// Returns the plan's runs: run -> config_hash.
std::map<std::string, std::string> onePlan(const std::string& folder, const std::map<std::string, ShardFiles>& shards) {
    const ShardFiles& reference = shards.begin()->second;
    for (const auto& [shard, files] : shards)
        for (const char* key : {"config_text", "overrides", "settings", "plan", "git_commit"}) {
            const std::string a = contextField(reference.json, reference.context, key),
                              b = contextField(files.json, files.context, key);
            if (a != b) {
                const std::string what = std::string(key) == "git_commit" ? "were run at other commits (" + a + " and " + b + ")"
                                         : std::string(key) == "plan" ? "have other plans"
                                         : std::string(key) == "overrides" ? "were run with other command-line overrides (" + a + " and " + b + ")"
                                         : std::string(key) == "settings" ? "were run with other --set (" + a + " and " + b + ")"
                                                                           : "were run from other config texts: the plans differ";
                throw Error(folder + ": " + reference.context.filename().string() + " and " +
                            files.context.filename().string() + " " + what + "; they cannot be merged");
            }
        }
    std::map<std::string, std::string> planned;
    try {
        for (const Json& run : reference.json.at("plan"))
            planned[run.at("run").get<std::string>()] = run.at("config_hash").get<std::string>();
    } catch (const Json::exception& e) {
        throw Error(reference.context.string() + ": no valid \"plan\" list: " + e.what());
    }
    if (planned.empty()) throw Error(reference.context.string() + ": its plan lists no runs");
    return planned;
}

// Every shard's rows by run: each in the plan, at the shards' commit, in one shard only. `complete`
// is false unless every shard says it is.
std::map<std::string, Row> shardRows(const std::string& folder, const std::map<std::string, ShardFiles>& shards,
                                     std::map<std::string, std::string>& planned, const std::string& commit, bool& complete) {
    std::map<std::string, Row> byRun;
    for (const auto& [shard, files] : shards) {
        const auto it = files.json.find("complete");
        if (it == files.json.end() || !it->is_boolean()) throw Error(files.context.string() + ": no boolean \"complete\" field");
        complete = complete && it->get<bool>();
        for (const Row& row : readRunsCsv(files.csv.string())) {
            const std::string& run = row.at("run");
            const std::string name = files.csv.filename().string() + ": run " + run + " (" + row.at("label") + ")";
            if (!planned.count(run) || planned[run] != row.at("config_hash")) throw Error(folder + ": " + name + " is not in the plan");
            if (row.at("git_commit") != commit) throw Error(folder + ": " + name + " was run at commit " + row.at("git_commit") + ", the shards at " + commit);
            if (!byRun.emplace(run, row).second) throw Error(folder + ": " + name + " appears in more than one shard");
        }
    }
    return byRun;
}

// Failed rows for the runs no shard finished, as the runner would have begun them.
void addMissingRuns(const ShardFiles& reference, const std::vector<std::string>& missing, std::map<std::string, std::string>& planned,
                    const std::string& commit, const std::string& missingReason, std::map<std::string, Row>& byRun) {
    const ExperimentPlan plan = recordedPlan(reference.json, reference.context.string());
    std::string device, driver, cpu = contextField(reference.json, reference.context, "cpu");
    if (!byRun.empty()) {
        const Row& any = byRun.begin()->second;
        device = any.at("device"), driver = any.at("driver"), cpu = any.at("cpu");
    } else if (const auto d = reference.json.find("devices"); d != reference.json.end() && d->is_array() && d->size() == 1) {
        device = d->at(0).value("name", ""), driver = d->at(0).value("driver", "");
    }
    for (const std::string& run : missing) {
        const auto it = std::find_if(plan.runs.begin(), plan.runs.end(), [&](const RunConfig& r) { return runNumber(r) == run; });
        if (it == plan.runs.end() || it->hash() != planned[run])
            throw Error(reference.context.string() + ": run " + run + " of its plan is not the run its config text gives");
        Row row = identityRow(*it, commit, device, driver, cpu);
        for (const std::string& column : runColumns()) row.emplace(column, "");  // every cell, as a read row has
        put(row, runColumnsDeclared().status, std::string("failed"));
        put(row, runColumnsDeclared().error, "no row from its shard: " + missingReason);
        byRun.emplace(run, std::move(row));
    }
}

// One device, and one content of each scene's files, across the shards.
void refuseMixedInputs(const std::string& folder, const std::map<std::string, Row>& byRun) {
    std::map<std::string, const Row*> byScene;
    const Row* firstRow = &byRun.begin()->second;
    for (const auto& [run, row] : byRun) {
        const auto machine = [](const Row& r) { return r.at("device") + " (" + r.at("driver") + ") with " + r.at("cpu"); };
        if (machine(row) != machine(*firstRow))
            throw Error(folder + ": run " + firstRow->at("run") + " ran on " + machine(*firstRow) + " and run " + run + " on " +
                        machine(row) + "; a merged runs.csv holds one device and CPU (Embree's speed depends on it)");
        if (row.at("inputs_hash").empty()) continue;  // the scene did not load: the row says why
        const std::string scene = row.at("scene_source");
        const auto [it, inserted] = byScene.emplace(scene, &row);
        if (!inserted && it->second->at("inputs_hash") != row.at("inputs_hash"))
            throw Error(folder + ": runs " + it->second->at("run") + " and " + run + " read other contents of scene.source '" + scene +
                        "' (" + it->second->at("input_files") + " against " + row.at("input_files") + ")");
    }
}

// A merged file may replace the same merge (merging again), never other results.
template <typename Read>
void refuseToReplace(const std::string& path, Read read, const std::vector<Row>& merge) {
    std::error_code ec;
    checkWritableFile(path);
    if (!fs::exists(fs::symlink_status(path, ec))) return;
    std::vector<Row> existing;
    try {
        existing = read(path);
    } catch (const Error& e) {
        throw Error(path + ": exists and is not the merge of these shards (" + e.what() + "); move it away first");
    }
    if (existing != merge)
        throw Error(path + ": exists and differs from the merge of these shards (" + std::to_string(existing.size()) +
                    " rows against " + std::to_string(merge.size()) + "); move it away first");
}

// The shards' timing samples, of the merged rows only, in run order (none: no shard has a
// samples file); every ok row's repetitions are there: as many kernel, Embree 1 and Embree 16
// samples as it says it took.
std::vector<Row> shardSamples(const std::string& folder, const std::map<std::string, ShardFiles>& shards,
                              const std::map<std::string, Row>& byRun, const std::vector<std::string>& missing, bool& withAny) {
    std::error_code ec;
    std::vector<Row> samples;
    std::size_t withSamples = 0;
    for (const auto& [shard, files] : shards) {
        const fs::path path = fs::path(folder) / ("samples." + shard + ".csv");
        if (!fs::exists(fs::symlink_status(path, ec))) continue;
        ++withSamples;
        for (Row& sample : readSamplesCsv(path.string())) {
            const auto row = byRun.find(sample.at("run"));
            // A run killed between its samples and its row left samples alone: its row is a stand-in.
            if (std::find(missing.begin(), missing.end(), sample.at("run")) != missing.end()) continue;
            if (row == byRun.end() || row->second.at("config_hash") != sample.at("config_hash"))
                throw Error(path.string() + ": a sample of run " + sample.at("run") + " (config_hash " + sample.at("config_hash") +
                            ") that no shard's row has");
            samples.push_back(std::move(sample));
        }
    }
    if (withSamples && withSamples != shards.size())
        throw Error(folder + ": " + std::to_string(withSamples) + " of " + std::to_string(shards.size()) +
                    " shards have a samples file; a shard's samples.shard-*.csv is missing");
    // Every ok row's repetitions are there: as many kernel, Embree 1 and Embree 16 samples as it
    // says it took.
    if (withSamples) {
        std::map<std::string, std::size_t> count;  // run|method
        for (const Row& sample : samples) ++count[sample.at("run") + "|" + sample.at("method")];
        for (const auto& [run, row] : byRun) {
            const auto reps = row.find("timing_repetitions");
            if (row.at("status") != "ok" || reps == row.end() || reps->second.empty()) continue;
            for (const char* method : {"kernel", "embree1", "embree16"})
                if (std::to_string(count[run + "|" + method]) != reps->second)
                    throw Error(folder + ": run " + run + " took " + reps->second + " repetitions of each method, the shards' samples hold " +
                                std::to_string(count[run + "|" + method]) + " of " + method);
        }
    }
    std::stable_sort(samples.begin(), samples.end(), [](const Row& a, const Row& b) { return a.at("run") < b.at("run"); });
    withAny = withSamples > 0;
    return samples;
}

}  // namespace

std::vector<Row> mergeShards(const std::string& folder, const std::string& missingReason) {
    refuseControlCharacters("--missing-as-failed: ", missingReason);  // it goes into every missing run's error
    std::error_code ec;
    if (!fs::is_directory(folder, ec)) throw Error(folder + ": not a results folder");
    refuseSymlinks(folder);  // before the lock file is made
    const OutputFolderLock lock(folder);  // no shard is running
    const FolderIdentity held(folder);     // the writes below go into this folder, whatever its path names later
    const std::map<std::string, ShardFiles> shards = findShards(folder);
    std::map<std::string, std::string> planned = onePlan(folder, shards);  // run -> config_hash
    const ShardFiles& reference = shards.begin()->second;
    const std::string commit = contextField(reference.json, reference.context, "git_commit");
    bool complete = true;
    std::map<std::string, Row> byRun = shardRows(folder, shards, planned, commit, complete);
    std::vector<std::string> missing;  // runs no shard finished: failed rows, and none of their samples
    for (const auto& [run, hash] : planned)
        if (!byRun.count(run)) missing.push_back(run);
    if (!missing.empty() && missingReason.empty()) throw Error(folder + ": run " + missing.front() + " is missing from the shards");
    if (!missing.empty()) {
        addMissingRuns(reference, missing, planned, commit, missingReason, byRun);
        complete = false;
    }
    refuseMixedInputs(folder, byRun);
    std::vector<Row> merged;
    for (const auto& [run, row] : byRun) merged.push_back(row);
    const std::string csvPath = (fs::path(folder) / "runs.csv").string();
    refuseToReplace(csvPath, [](const std::string& path) { return readRunsCsv(path); }, merged);
    bool withSamples = false;
    const std::vector<Row> samples = shardSamples(folder, shards, byRun, missing, withSamples);
    const std::string samplesPath = (fs::path(folder) / "samples.csv").string();
    if (withSamples)
        refuseToReplace(samplesPath, readSamplesCsv, samples);
    else
        checkWritableFile(samplesPath);
    writeCsv(csvPath, runColumns(), merged);
    if (withSamples) writeCsv(samplesPath, sampleColumns(), samples);
    Json context = reference.json;
    context["complete"] = complete;
    context["shard"] = "";
    writeJson((fs::path(folder) / "context.json").string(), context);
    return merged;
}

}  // namespace rtbench
