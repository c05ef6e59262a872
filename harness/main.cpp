// rtbench: GPU ray tracing strategies measured against Embree, from TOML experiment configs.
#include <CLI/CLI.hpp>

#include <spawn.h>
#include <sys/wait.h>

#include <cerrno>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "harness/check.h"
#include "harness/compare.h"
#include "harness/columns.h"
#include "harness/config.h"
#include "harness/images.h"
#include "harness/retime.h"
#include "harness/unpack.h"
#include "harness/plan_view.h"
#include "harness/runner.h"
#include "harness/shard_merge.h"
#include "harness/version.h"
#include "device/vulkan_context.h"
#include "core/error.h"
#include "scene/mesh_io.h"
#include "scene/procedural.h"

namespace {

// Runs a program with an argument vector (no shell) and waits; its exit status, or 127.
int runProgram(const std::vector<std::string>& argv) {
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    pid_t pid = 0;
    if (posix_spawn(&pid, args[0], nullptr, nullptr, args.data(), environ) != 0) return 127;
    int status = 0;
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR) return 127;
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// scripts/plot.py beside the binary (build/rtbench -> scripts/, or a bundle's scripts/), else in
// the source tree the binary was built from.
std::string findPlotScript() {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    std::vector<fs::path> candidates;
    if (!ec) candidates = {exe.parent_path() / "scripts" / "plot.py", exe.parent_path().parent_path() / "scripts" / "plot.py"};
    candidates.push_back(fs::path(RTBENCH_SOURCE_DIR) / "scripts" / "plot.py");
    std::string tried;
    for (const fs::path& p : candidates) {
        if (fs::is_regular_file(p, ec)) return p.string();
        tried += (tried.empty() ? "" : ", ") + p.string();
    }
    throw rtbench::Error("scripts/plot.py not found (looked at " + tried + ")");
}

// `rtbench meshes`: each scene source with its triangle count and bounding size, to choose by; a
// mesh that does not load says why on its line.
void printMeshes(std::ostream& out) {
    auto line = [&](const std::string& source, auto load) {
        char text[160];
        try {
            const rtbench::TriangleMesh mesh = load();
            const glm::vec3 extent = mesh.bounds().extent();
            std::snprintf(text, sizeof text, "%10zu  %9.3g x %9.3g x %9.3g", mesh.triangles.size(),
                          double(extent.x), double(extent.y), double(extent.z));
        } catch (const std::exception& e) {
            out << std::left << std::setw(34) << source << "  does not load: " << e.what() << "\n";
            return;
        }
        out << std::left << std::setw(34) << source << text << "\n";
    };
    out << std::left << std::setw(34) << "scene.source" << " triangles  bounding size (x by y by z)\n";
    for (const std::string& name : rtbench::proceduralSceneNames())
        line("procedural:" + name, [&] { return rtbench::proceduralScene(name); });
    for (const std::string& name : rtbench::cgalMeshNames())
        line("cgal:" + name, [&] { return rtbench::readCgalMesh(name); });
}

// Each subcommand: its options, registered on the app, and what it does once parsed. The
// command line as typed (`commandLine`) is set before any runs (context.json records it).
struct Command {
    CLI::App* app;
    std::function<int()> run;
};
using Commands = std::vector<Command>;

const char* const kSetHelp = "set a config key over the file, e.g. --set structure.min_dim=[16,32] (TOML; a list sweeps); "
                             "checked as in the file, recorded in context.json and in each run's identity; repeatable";
const char* const kFilterHelp = "only runs with key=value (e.g. structure.type=bvh), or whose label holds this text; repeatable";

// --shard i/N as RunnerOptions' index and count.
void parseShard(const std::string& shard, rtbench::RunnerOptions& options) {
    unsigned i = 0, n = 0;
    char slash = 0;
    std::istringstream in(shard);
    if (!(in >> i >> slash >> n) || slash != '/' || n == 0 || i >= n || !in.eof())
        throw rtbench::Error("--shard " + shard + ": expected i/N with 0 <= i < N, e.g. 0/3");
    options.shardIndex = i;
    options.shardCount = n;
}

// What `rtbench run` says at its end: the summary table, the files in the folder, ok and failed.
int reportRun(const rtbench::ExperimentResult& result, const rtbench::RunnerOptions& options) {
    namespace fs = std::filesystem;
    std::cout << "\n" << rtbench::summaryTable(result.rows);
    if (result.reused) std::cout << "(" << result.reused << " run(s) kept from an earlier invocation; --force re-runs them)\n";
    if (result.warned && options.quiet)
        std::cout << result.warned << " run(s) with a warning (columns warnings, timing_warning: a timing warning means "
                  << "the run's timings are not results of record); without -q each is said as it runs\n";
    std::string files;  // the files that are there now, by name
    for (const std::string& name : {rtbench::runsFileName(options), rtbench::samplesFileName(options), rtbench::contextFileName(options)})
        if (fs::is_regular_file(fs::path(result.folder) / name)) files += (files.empty() ? "" : ", ") + name;
    int pngs = 0, hits = 0;
    for (const rtbench::Row& row : result.rows) {
        const fs::path prefix = fs::path(result.folder) / ("run-" + row.at("run"));
        pngs += fs::is_regular_file(prefix.string() + "-shaded.png");
        hits += fs::is_regular_file(prefix.string() + ".hits");
    }
    if (pngs) files += ", " + std::to_string(pngs) + " run(s)' PNGs";
    if (hits) files += ", " + std::to_string(hits) + " run(s)' hit records (.hits, for `rtbench images`)";
    std::cout << "\nresults in " << result.folder << "/: " << files << " — " << result.rows.size() - result.failed << " ok, "
              << result.failed << " failed"
              << (options.shardCount > 1 ? "; `rtbench merge " + result.folder + "` once every shard is done" : "") << "\n";
    return result.failed ? 1 : 0;
}

void addRun(CLI::App& app, Commands& commands, const std::string& commandLine) {
    struct Options {
        std::string config, device, embreeConfig, shard;
        bool validation = false, dryRun = false;
        std::vector<std::string> settings;
        rtbench::RunnerOptions runner;
    };
    auto o = std::make_shared<Options>();
    CLI::App* run = app.add_subcommand("run", "Run every run of an experiment config (list-valued keys sweep)");
    run->add_option("config", o->config, "experiment config (TOML), e.g. configs/bunny.toml")->required();
    run->add_option("-o,--output", o->runner.outputOverride, "output folder (overrides experiment.output)");
    run->add_option("-d,--device", o->device, "Vulkan device: auto, or a substring of its name or driver, e.g. \"Mesa 25\" (overrides device.name)");
    run->add_flag("--validation", o->validation, "enable the Vulkan validation layer (a run fails on any message) and fill new device buffers with NaNs");
    run->add_flag("-q,--quiet", o->runner.quiet, "print only the summary table");
    run->add_flag("-f,--force", o->runner.force, "re-run runs whose rows (same run, config hash, commit) already exist");
    run->add_option("--embree-config", o->embreeConfig,
                    "Embree device config string for every run (overrides baseline.embree_config), e.g. isa=avx2");
    run->add_option("--shard", o->shard, "run only every N-th run, starting at i (0 <= i < N), e.g. 2/3; join with `rtbench merge`");
    run->add_flag("--dry-run", o->dryRun, "print the plan (as `rtbench plan`) and run nothing");
    run->add_option("--set", o->settings, kSetHelp)->allow_extra_args(false);
    run->add_option("--filter", o->runner.filters, std::string(kFilterHelp) + "; the other runs' rows stay as they are")
        ->allow_extra_args(false);
    commands.push_back({run, [o, &commandLine] {
        o->runner.commandLine = commandLine;
        if (!o->shard.empty()) parseShard(o->shard, o->runner);
        rtbench::ExperimentPlan plan = rtbench::loadExperiment(o->config, o->settings);
        if (!o->embreeConfig.empty()) rtbench::overrideEmbreeConfig(plan, o->embreeConfig);
        // The effective device and validation are the run's parameters (and identity).
        if (!o->device.empty()) rtbench::overrideKey(plan, "device.name", o->device, "-d");
        if (o->validation) rtbench::overrideKey(plan, "device.validation", true, "--validation");
        if (o->dryRun) {
            std::cout << rtbench::describePlan(plan, o->runner, o->runner.filters);
            return 0;
        }
        return reportRun(rtbench::runExperiment(plan, o->runner), o->runner);
    }});
}

void addPlanAndLists(CLI::App& app, Commands& commands) {
    struct Options {
        std::string config, output;
        std::vector<std::string> filters, settings;
        bool columnsAsCsv = false;
    };
    auto o = std::make_shared<Options>();
    CLI::App* plan = app.add_subcommand("plan", "Print every run of a config with its swept parameters and what an earlier row of it took, without running");
    plan->add_option("config", o->config, "experiment config (TOML)")->required();
    plan->add_option("--filter", o->filters, kFilterHelp)->allow_extra_args(false);
    plan->add_option("--set", o->settings, kSetHelp)->allow_extra_args(false);
    plan->add_option("-o,--output", o->output, "output folder (overrides experiment.output), where earlier rows are looked for");
    commands.push_back({plan, [o] {
        rtbench::RunnerOptions options;
        options.outputOverride = o->output;
        std::cout << rtbench::describePlan(rtbench::loadExperiment(o->config, o->settings), options, o->filters);
        return 0;
    }});
    commands.push_back({app.add_subcommand("meshes", "List the procedural:NAME scenes and cgal:NAME meshes (Debian's libcgal-demo) with their triangles and bounding sizes"),
                        [] { printMeshes(std::cout); return 0; }});
    commands.push_back({app.add_subcommand("devices", "List the Vulkan devices rtbench can use"), [] {
        for (const rtbench::DeviceInfo& d : rtbench::VulkanContext::listDevices())
            std::cout << d.name << "\n  driver: " << d.driver << "\n  Vulkan " << d.apiVersion << ", type " << d.type
                      << ", subgroup size " << d.subgroupSize << "\n  maxStorageBufferRange " << d.maxStorageBufferRange
                      << " bytes, maxComputeWorkGroupCount[0] " << d.maxWorkGroupCountX << ", push constants "
                      << d.maxPushConstantsSize << " bytes\n  device-local heap " << d.deviceLocalBytes
                      << " bytes, timestamps " << (d.timestampsSupported ? "yes" : "no") << " (period "
                      << d.timestampPeriodNs << " ns)\n  ray query (VK_KHR_ray_query): "
                      << (d.rayQuery ? "yes" : "no, missing " + d.rayQueryMissing) << "\n";
        return 0;
    }});
    commands.push_back({app.add_subcommand("keys", "List every config key with its type, default and meaning"), [] {
        for (const rtbench::KeySpec& k : rtbench::configSchema())
            std::cout << k.name << (k.required ? " (required)" : "")
                      << (k.defaultValue ? " = " + rtbench::formatValue(*k.defaultValue) : std::string()) << "  ("
                      << rtbench::keyTypeText(k) << ")\n    " << k.help << "\n";
        return 0;
    }});
    CLI::App* columns = app.add_subcommand("columns", "List the metric columns of runs.csv: kind, value type, unit, meaning (Markdown)");
    columns->add_flag("--csv", o->columnsAsCsv, "every column, config keys included, as the columns.csv a run writes beside runs.csv");
    commands.push_back({columns, [o] {
        std::cout << (o->columnsAsCsv ? rtbench::columnsCsv() : rtbench::columnsMarkdown());
        return 0;
    }});
}

// The commands on a results folder that make files in it or beside it: merge, images, plot, unpack.
void addFolderMakers(CLI::App& app, Commands& commands) {
    struct Options {
        std::string merge, missingAsFailed, images, plot, archive, unpackDir;
        bool plotVerbose = false;
        CLI::Option* missingOption = nullptr;
    };
    auto o = std::make_shared<Options>();
    CLI::App* merge = app.add_subcommand("merge", "Join the runs.shard-*.csv of a results folder into runs.csv, checking none is missing or doubled");
    merge->add_option("results_dir", o->merge, "results folder of a sharded run")->required();
    o->missingOption = merge->add_option("--missing-as-failed", o->missingAsFailed,
                      "write a failed row, its error \"no row from its shard: REASON\", for each run no shard finished "
                      "(a shard killed by a time limit or never started) instead of refusing; context.json then says "
                      "complete: false");
    commands.push_back({merge, [o] {
        if (o->missingOption->count() && o->missingAsFailed.find_first_not_of(" \t") == std::string::npos)
            throw rtbench::Error("--missing-as-failed: give the reason the missing runs failed (it goes into their error)");
        const std::vector<rtbench::Row> rows = rtbench::mergeShards(o->merge, o->missingAsFailed);
        std::cout << "merged " << rows.size() << " runs into " << o->merge << "/runs.csv\n";
        return 0;
    }});
    CLI::App* images = app.add_subcommand("images", "Write PNGs from the per-ray hit records (*.hits) of a results folder");
    images->add_option("results_dir", o->images, "folder holding run-NNN.hits files")->required();
    commands.push_back({images, [o] {
        // Each bad .hits file is reported with its reason, the others still converted.
        const rtbench::ImagesReport report = rtbench::imagesForFolder(o->images);
        for (const std::string& w : report.warnings) std::cerr << "rtbench: warning: " << w << "\n";
        for (const std::string& f : report.failures) std::cerr << "rtbench: error: " << f << "\n";
        std::cout << "wrote images for " << report.written << " of " << report.hitsFiles() << " run(s) in " << o->images << "\n";
        return report.failures.empty() ? 0 : 1;
    }});
    CLI::App* plot = app.add_subcommand("plot", "Write PNG and SVG charts next to a results folder's runs.csv (scripts/plot.py)");
    plot->add_option("results_dir", o->plot, "results folder")->required();
    plot->add_flag("-v,--verbose", o->plotVerbose, "also name each chart these runs do not call for, and why");
    commands.push_back({plot, [o] {
        // Debian's python3-matplotlib and python3-pandas (PyPI is not reachable here). Charts are
        // written into the folder: never into a linked one (plot.py refuses linked chart files,
        // writing each through a temporary and os.replace).
        std::error_code ec;
        if (std::filesystem::is_symlink(std::filesystem::symlink_status(o->plot, ec)))
            throw rtbench::Error(o->plot + ": the results folder is a symlink; give the folder it points to");
        std::vector<std::string> argv{"/usr/bin/python3", findPlotScript()};
        if (o->plotVerbose) argv.push_back("-v");
        argv.push_back(o->plot);
        return runProgram(argv) == 0 ? 0 : 1;
    }});
    CLI::App* unpack = app.add_subcommand("unpack", "Unpack a GPU campaign's archive (scripts/gpu_campaign.sh run) into a folder, trusting nothing in it: CONFIG/FILE regular files and plain folders only, names and modes checked, sizes capped; exit 1 naming the first refused entry, nothing unpacked");
    unpack->add_option("archive", o->archive, "the campaign's tar archive (.tar, .tar.gz, .tar.xz)")->required();
    unpack->add_option("dir", o->unpackDir, "the folder to unpack into (made if absent; never a link)")->required();
    commands.push_back({unpack, [o] {
        const std::vector<std::string> files = rtbench::unpackCampaign(o->archive, o->unpackDir);
        std::cout << o->unpackDir << ": " << files.size() << " file(s) unpacked\n";
        return 0;
    }});
}

// The commands that judge results folders: check, retime, compare.
void addJudges(CLI::App& app, Commands& commands) {
    struct Options {
        std::string check, retime, compareA, compareB;
        rtbench::CheckOptions checkOptions;
        rtbench::RetimeOptions retimeOptions;
        rtbench::CompareOptions compareOptions;
    };
    auto o = std::make_shared<Options>();
    CLI::App* check = app.add_subcommand("check", "Re-run a results folder's config and compare: counts exactly (exit 1 on a difference), timings within a tolerance");
    check->add_option("results_dir", o->check, "results folder (runs.csv and context.json)")->required();
    check->add_option("--tolerance", o->checkOptions.timingTolerance, "relative tolerance for timing columns (default 0.5 = 50%)");
    check->add_option("--embree-config", o->checkOptions.embreeConfigOverride,
                      "re-run with this Embree config string (e.g. isa=sse4.2): counts must not change");
    commands.push_back({check, [o] { return rtbench::checkResults(o->check, o->checkOptions, std::cout).failed() ? 1 : 0; }});
    CLI::App* retime = app.add_subcommand("retime", "Re-time the runs of a results folder that have a timing warning, up to --tries times each; keep the better-conditioned samples (column retimed says which and why); exit 1 if a count moved");
    retime->add_option("results_dir", o->retime, "results folder recorded by this binary on this machine")->required();
    retime->add_option("--tries", o->retimeOptions.tries, "re-runs of each flagged run at most (default 3; a run stops once it times clean)");
    commands.push_back({retime, [o] {
        const rtbench::RetimeResult result = rtbench::retimeFlagged(o->retime, o->retimeOptions, std::cout);
        for (const std::string& d : result.differences) std::cerr << "rtbench: deterministic difference: " << d << "\n";
        if (result.failed()) std::cerr << "rtbench: error: a re-run's counts differ from the record; nothing written\n";
        return result.failed() ? 1 : 0;
    }});
    rtbench::CompareOptions& c = o->compareOptions;
    CLI::App* compare = app.add_subcommand("compare", "Compare two results folders run by run: a verdict SAME, FASTER, SLOWER or UNSURE from the kernel's median change, its interval and a Holm-corrected Mann-Whitney p-value; counts exactly (exit 1 on SLOWER or a count difference, 2 when no run matched)");
    compare->add_option("a", o->compareA, "the baseline results folder")->required();
    compare->add_option("b", o->compareB, "the results folder compared with it")->required();
    compare->add_option("--threshold", c.threshold, "a change counts beyond this fraction (default 0.05 = 5%)");
    compare->add_option("--alpha", c.alpha, "significance level of the Mann-Whitney U test after Holm's correction (default 0.05)");
    compare->add_option("--relative-to", c.relativeTo, "embree1: judge the kernel's time over Embree rtcIntersect1's on the same rays (a machine slower as a whole is no regression); default: the kernel's time");
    compare->add_option("--ignore", c.ignore, "a config key not matched on, so that runs meet across its values (repeatable)");
    auto* markdown = compare->add_flag("--markdown", c.markdown, "print a Markdown table");
    compare->add_flag("--json", c.json, "print the verdicts as JSON (docs/commands.md)")->excludes(markdown);
    commands.push_back({compare, [o] {
        const rtbench::CompareResult result = rtbench::compareFolders(o->compareA, o->compareB, o->compareOptions);
        rtbench::printComparison(result, o->compareA, o->compareB, o->compareOptions, std::cout);
        return result.exitStatus();
    }});
}

// A first word that is no subcommand is named (CLI11 would only say one is required): false then.
bool knownSubcommand(CLI::App& app, int argc, char** argv) {
    if (argc <= 1 || argv[1][0] == '-') return true;
    std::string known;
    bool found = false;
    for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
        known += (known.empty() ? "" : ", ") + sub->get_name();
        found = found || sub->get_name() == argv[1];
    }
    if (!found) std::cerr << "rtbench: error: unknown subcommand '" << argv[1] << "' (subcommands: " << known << "; rtbench --help)\n";
    return found;
}

}  // namespace

static int runCommand(int argc, char** argv) {
    CLI::App app{"rtbench: GPU ray tracing strategies (Purcell 2002, Christen 2005) measured against Embree"};
    app.require_subcommand(1);
    app.set_version_flag("--version", rtbench::versionText(), "print the version, the commit it was built from and the build type");
    std::string commandLine;
    Commands commands;
    addRun(app, commands, commandLine);
    addPlanAndLists(app, commands);
    addFolderMakers(app, commands);
    addJudges(app, commands);
    if (!knownSubcommand(app, argc, argv)) return 2;
    CLI11_PARSE(app, argc, argv);
    for (int i = 0; i < argc; ++i) commandLine += (i ? " " : "") + std::string(argv[i]);
    try {
        for (const Command& command : commands)
            if (*command.app) return command.run();
    } catch (const std::exception& e) {
        std::cerr << "rtbench: error: " << e.what() << "\n";
        return 2;
    }
    return 0;
}

int main(int argc, char** argv) {
    const int status = runCommand(argc, argv);
    // What a command printed must have reached its reader: a full disk or a closed pipe behind
    // stdout (rtbench columns --csv > /dev/full) is a failure, not exit 0.
    std::cout.flush();
    if (!std::cout) {
        std::cerr << "rtbench: error: cannot write to standard output (a full disk or a closed pipe?)\n";
        return status ? status : 2;
    }
    return status;
}
