#include "columns.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

#include "build_rounds.h"
#include "config.h"
#include "methods/cache/cache_replay.h"
#include "methods/registry.h"
#include "run_inputs.h"
#include "run_metrics.h"
#include "run_pipeline.h"
#include "rays/registry.h"
#include "core/error.h"
#include "core/input_file.h"

namespace rtbench {

namespace {

// The columns added before schema numbers were recorded (schema/columns.h), by the schema that added
// them; the rest of the columns of those days are schema 1, and later ones declare their own.
int addedInSchema(const std::string& column) {
    static const std::map<std::string, int> added = [] {
        std::map<std::string, int> m;
        for (const char* c : {"scene_scale", "scene_translate", "structure_conservative", "grid_voxel_margin", "intersection_test",
                              "accuracy_exact_rays", "exact_rays", "exact_ties", "exact_ms"})
            m[c] = 2;
        for (const char* p : {"exact_", "embree_exact_"})
            for (const char* c : {"false_misses", "false_hits", "wrong_primitive", "wrong_ppm", "distance_error_mean", "distance_error_max"})
                m[std::string(p) + c] = 2;
        for (const char* c : {"scene_simplify_ratio", "scene_simplify_triangles", "intersection_vertex_bits", "scene_full_triangles",
                              "scene_simplify_ms", "vertex_lattice_step", "vertex_snap_error_max", "image_psnr_db",
                              "image_error_mean", "image_error_max", "image_pixels_differ"})
            m[c] = 3;
        for (const char* c : {"inputs_hash", "input_files", "cpu"}) m[c] = 4;
        return m;
    }();
    const auto it = added.find(column);
    return it == added.end() ? 1 : it->second;
}

// The columns of runs.csv as they are declared, in their order.
struct ColumnList {
    std::vector<ColumnSpec> specs;

    ColumnSpec& add(std::string name, ColumnKind kind, std::string unit, std::string help, double tolerance = 0.0,
                    bool perRay = false) {
        specs.push_back({std::move(name), kind, std::move(unit), std::move(help), tolerance, perRay});
        return specs.back();
    }
    // A column whose cells name or explain (a label, a hash, a reason).
    ColumnSpec& text(std::string name, ColumnKind kind, std::string help) {
        return specs.emplace_back(textColumn({std::move(name), kind, "", std::move(help)}));
    }
    // A part's typed columns (schema/column.h), in their order.
    void append(const std::vector<ColumnSpec>& columns) { specs.insert(specs.end(), columns.begin(), columns.end()); }
    // A structure's, ray type's or strategy's own columns, written only by its runs (`typeKey` =
    // `name`). A column several methods write (rays_cut_short, the lane model's lanes_model_*) is
    // declared by each, alike: its condition names them all.
    void addMethod(const std::string& typeKey, const std::string& name, const std::vector<ColumnSpec>& columns) {
        for (ColumnSpec c : columns) {
            auto same = std::find_if(specs.begin(), specs.end(), [&](const ColumnSpec& d) { return d.name == c.name; });
            if (same != specs.end() && !same->appliesWhen.empty() && same->appliesWhen.front().rfind(typeKey + "=", 0) == 0 &&
                same->help == c.help && same->kind == c.kind && same->unit == c.unit && same->since == c.since &&
                same->type == c.type) {
                same->appliesWhen.front() += "|" + name;
                continue;
            }
            c.appliesWhen.insert(c.appliesWhen.begin(), typeKey + "=" + name);
            specs.push_back(std::move(c));
        }
    }
};

ColumnType keyColumnType(ValueType type) {
    switch (type) {
        case ValueType::Int:
        case ValueType::Int3: return ColumnType::Integer;
        case ValueType::Float:
        case ValueType::Float3: return ColumnType::Number;
        case ValueType::Bool: return ColumnType::Boolean;
        case ValueType::String: break;
    }
    return ColumnType::Text;
}

// One column per config key (a 3-vector key: three), of the key's type.
void addKeyColumns(ColumnList& s) {
    for (const KeySpec& key : configSchema()) {
        const std::vector<std::string> columns = keyColumns(key);
        for (std::size_t a = 0; a < columns.size(); ++a) {
            ColumnSpec& c = s.add(columns[a], key.name == "experiment.output" ? ColumnKind::Context : ColumnKind::Parameter, "",
                                  columns.size() == 1 ? key.help : key.help + " (" + "xyz"[a] + ")");
            c.appliesWhen = key.appliesWhen;
            c.since = std::max(key.since, addedInSchema(paramColumn(key.name)));
            c.type = keyColumnType(key.type);
        }
    }
}

// Identity and outcome.
void addIdentityColumns(ColumnList& s) {
    using K = ColumnKind;
    s.text("run", K::Parameter, "run number in the plan (000, 001, ...)");
    s.text("label", K::Parameter, "the swept parameters of the run");
    s.text("sweep", K::Parameter, "the name of the [[sweep]] the run comes from (empty: the base config)").since = 5;
    s.text("status", K::Exact, "ok or failed");
    s.text("error", K::Exact, "why the run failed");
    s.text("warnings", K::Exact, "what the run did that may surprise (e.g. triangles degenerate in float)");
    s.text("config_hash", K::Parameter, "FNV-1a 64 of the run's parameters (the command line's -d, --validation and --embree-config included)");
    s.text("inputs_hash", K::Parameter, "FNV-1a 64 over the contents of every file the scene was made from (mesh files, the scene description and its meshes, a cgal: mesh's cached file; none for procedural scenes): with config_hash, git_commit, device, driver and cpu, the run's identity");
    s.text("input_files", K::Context, "those files: path (bytes, FNV-1a 64 of the contents), in reading order");
    s.text("git_commit", K::Context, "commit of the binary");
    s.text("device", K::Context, "Vulkan device name");
    s.text("driver", K::Context, "Vulkan driver name and version");
    s.text("cpu", K::Context, "the host's CPU model (what lavapipe and Embree ran on)");
}

// Scene, rays, the shading passes that made them, and the structure.
void addSceneColumns(ColumnList& s) {
    s.append(sceneInputColumns());          // harness/run_inputs.cpp
    s.append(batchColumns());               // harness/run_pipeline.cpp
    s.append(shadingColumns());             // rays/workload.cpp
    s.append(cameraAndStructureColumns());  // harness/run_pipeline.cpp
}

// How the timing went, and the noise guard's judgement of it (harness/timing_rounds.h).
void addNoiseGuardColumns(ColumnList& s) {
    using K = ColumnKind;
    s.add("timing_repetitions", K::Timing, "repetitions", "timed repetitions of each method (kernel, Embree 1, Embree 16)").since = 5;
    s.add("timing_rounds", K::Timing, "rounds", "rounds they were timed in, each the kernel then Embree 1 then Embree 16").since = 5;
    s.text("timing_stop", K::Timing, "why the timing stopped: repetitions (experiment.repetitions, fixed), converged (every interval within experiment.target_ci), max_repetitions, time_budget").since = 5;
    s.add("timing_s", K::Timing, "s", "wall time of the timed rounds (with experiment.target_ci, the judging after each included: what experiment.time_budget_s bounds)").since = 5;
    s.text("timing_warning", K::Context, "noise guard: why the run's timings are not results of record (a median's 95% interval wider than +- experiment.noise_ci of it, or below 6 repetitions a coefficient of variation above experiment.noise_cv; other processes above experiment.noise_other_cpu, one repetition: noise not measured); empty when clean").since = 5;
    s.text("retimed", K::Context, "rtbench retime: when the run was re-timed, which try's timings were kept and why (no timing warning beats one, then the narrower widest spread: a median's interval half-width, or below 6 repetitions the CV), or that none was better conditioned; empty when never re-timed").since = 24;
    s.add("other_cpu_fraction", K::Timing, "fraction", "noise guard: CPU time other processes took while the run ran (from its scene to the end of its timing), over cores x wall time (Linux /proc/stat, hypervisor steal included); empty when that window held under 100 clock ticks of the machine").since = 5;
    s.add("load_average", K::Timing, "", "noise guard: 1-minute load average when the timing ended").since = 5;
    s.add("device_host_threads", K::Context, "threads", "threads the device runs on the host's cores (lavapipe: LP_NUM_THREADS, else one per core up to 32; 0 for a GPU), beside embree_threads, against the machine's cores (context.json cpu_threads)").since = 5;
}

// A timed method's spread: mean, std, CV and the median's interval (harness/timing_rounds.h).
void addSpreadColumns(ColumnList& s, const std::string& m, const std::string& who) {
    using K = ColumnKind;
    s.add(m + "_ms_mean", K::Timing, "ms", who + ", mean of the repetitions").since = 5;
    s.add(m + "_ms_std", K::Timing, "ms", who + ", sample standard deviation of the repetitions (empty for one)").since = 5;
    s.add(m + "_ms_cv", K::Timing, "", who + ", coefficient of variation (std / mean; empty for one repetition)").since = 5;
    s.add(m + "_ms_ci_low", K::Timing, "ms", who + ", 95% interval of the median from the order statistics "
          "(distribution-free, coverage at least 95%; empty below 6 repetitions; before results schema 23: "
          "percentile bootstrap): low end").since = 5;
    s.add(m + "_ms_ci_high", K::Timing, "ms", who + ", 95% interval of the median (as _ci_low): high end").since = 5;
}

// Time: the kernel's and Embree's on the same rays (every sample is in samples.csv).
void addTimingColumns(ColumnList& s) {
    using K = ColumnKind;
    s.add("kernel_ms_median", K::Timing, "ms",
          "GPU time of the kernel(s), median of the repetitions (multipass with strategy.control = host, "
          "since results schema 25: host wall time of its live pass loop, the oracle's read-back after every pass)");
    s.add("kernel_ms_min", K::Timing, "ms", "GPU time, fastest repetition");
    s.add("kernel_ms_max", K::Timing, "ms", "GPU time, slowest repetition");
    addSpreadColumns(s, "kernel", "GPU time");
    s.add("kernel_mrays_s", K::Timing, "Mrays/s", "rays / median GPU time (the rays of every generation for a strategy that traces the whole path: whole_path_rays)");
    for (const std::string m : {"embree1", "embree16"}) {
        s.add(m + "_ms_median", K::Timing, "ms", "Embree " + m + " on the same rays, median");
        s.add(m + "_ms_min", K::Timing, "ms", "Embree " + m + ", fastest repetition");
        s.add(m + "_ms_max", K::Timing, "ms", "Embree " + m + ", slowest repetition");
        addSpreadColumns(s, m, "Embree " + m);
        s.add(m + "_mrays_s", K::Timing, "Mrays/s", "rays / Embree's median time");
    }
    s.add("embree_rays", K::Exact, "rays",
          "rays Embree traced per repetition: the batch's, or beside a strategy that traces the whole path (wavefront, "
          "path_megakernel) every generation's, as the kernel did").since = 19;
    s.add("embree_threads", K::Context, "threads", "TBB threads Embree ran on");
    s.text("embree_isa", K::Context, "Embree's native packet width (its ISA path)");
    s.add("embree_build_ms", K::Timing, "ms", "Embree BVH build time");
    s.add("speed_ratio_vs_embree1", K::Timing, "ratio", "kernel Mrays/s / Embree rtcIntersect1 Mrays/s");
    s.add("speed_ratio_ci_low", K::Timing, "ratio", "speed_ratio_vs_embree1: 95% interval, from each median's 97.5% "
          "order-statistic interval (both hold at once with at least 95%; empty below 7 repetitions; before results "
          "schema 23: percentile bootstrap), low end").since = 5;
    s.add("speed_ratio_ci_high", K::Timing, "ratio", "speed_ratio_vs_embree1: 95% interval (as _ci_low), high end").since = 5;
    addNoiseGuardColumns(s);
}

// Agreement with Embree (a second view of accuracy: depends on Embree's floating-point path),
// accuracy against the exact reference (harness/exact_reference.h: the kernels' counts are
// deterministic, Embree's depend on its ISA path), and the image against the exact render.
void addAccuracyColumns(ColumnList& s) {
    using K = ColumnKind;
    s.append(agreementColumns());  // harness/run_pipeline.cpp
    s.add("exact_rays", K::Exact, "rays", "rays traced by the exact reference (accuracy.exact_rays)");
    s.add("exact_ties", K::Exact, "rays", "of those, rays whose exact first hit is shared by several triangles (each is correct)");
    s.add("exact_ms", K::Timing, "ms", "wall time of the exact reference on those rays");
    s.add("exact_parent_wrong", K::Exact, "rays", "rays after the first hit: of the exact_rays, those with a ray earlier on their path (the camera ray, an earlier reflection) whose hit is not an exact first hit (they leave from another surface than the exact scene's; still judged as the rays they are)").since = 7;
    s.append(exactColumns(false));  // harness/run_metrics.cpp: the kernel's, then Embree's
    s.append(exactColumns(true));
    s.append(imageColumns());
}

// Self-checks (a mismatch fails the run), and the run's wall time.
void addSelfCheckColumns(ColumnList& s) {
    using K = ColumnKind;
    s.add("cpu_reference_mismatches", K::Exact, "rays",
          "rays whose GPU hit record differs from the CPU reference's (empty for the driver's ray query: another's arithmetic, judged by the exact reference)");
    s.add("cpu_counts_match", K::Exact, "",
          "1 when pass and lane counts equal the CPU reference's (lane counts only on a device whose subgroups run "
          "in lock step; empty for branching elsewhere, where they are not compared)").type = ColumnType::Integer;
    s.add("wall_s", K::Timing, "s", "wall time of the whole run");
}

// A column of inferred type: an integer when its unit counts things and it is not a mean or a
// per-something ratio (a per-ray maximum is a count), else a number.
ColumnType inferredType(const ColumnSpec& column) {
    static const std::set<std::string> countedUnits = {"rays", "triangles", "bytes", "passes", "cells", "references", "nodes",
                                                       "leaves", "levels", "voxels", "tests", "steps", "pixels", "threads", "lights",
                                                       "materials", "repetitions", "rounds", "generations"};
    const std::string& n = column.name;
    const bool averaged = n.find("_mean") != std::string::npos || (n.find("_per_") != std::string::npos && !n.ends_with("_max"));
    return countedUnits.count(column.unit) && !averaged ? ColumnType::Integer : ColumnType::Number;
}

}  // namespace

const std::vector<ColumnSpec>& runColumnSpecs() {
    static const std::vector<ColumnSpec> specs = [] {
        ColumnList s;
        addKeyColumns(s);
        addIdentityColumns(s);
        addSceneColumns(s);
        for (const StructureType* t : structureTypes()) s.addMethod("structure.type", t->name, t->columns);
        for (const RayType* t : rayTypes()) s.addMethod("rays.type", t->name, t->columns);
        addTimingColumns(s);
        for (const ColumnSpec& c : buildRoundColumns()) s.specs.push_back(c);  // experiment.build_rounds
        addAccuracyColumns(s);
        s.append(architectureColumns());  // harness/run_metrics.cpp
        for (const StrategyType* t : strategyTypes()) s.addMethod("strategy.type", t->name, t->columns);
        for (const ColumnSpec& c : cacheColumns()) s.specs.push_back(c);  // cache.simulate
        addSelfCheckColumns(s);
        std::set<std::string> names;
        for (ColumnSpec& c : s.specs) {
            c.since = std::max(c.since, addedInSchema(c.name));
            if (c.type == ColumnType::Inferred) c.type = inferredType(c);
            if (!names.insert(c.name).second) throw Error("column '" + c.name + "' is declared twice");
        }
        return s.specs;
    }();
    return specs;
}

std::vector<std::string> runColumns() {
    std::vector<std::string> names;
    for (const ColumnSpec& c : runColumnSpecs()) names.push_back(c.name);
    return names;
}

const ColumnSpec& columnSpec(const std::string& name) {
    static const std::map<std::string, const ColumnSpec*> byName = [] {
        std::map<std::string, const ColumnSpec*> m;
        for (const ColumnSpec& c : runColumnSpecs()) m[c.name] = &c;
        return m;
    }();
    const auto it = byName.find(name);
    if (it == byName.end())
        throw Error("column '" + name + "' is not declared (harness/columns.cpp or a method's own columns)");
    return *it->second;
}

std::string columnsMarkdown() {
    std::string out = "| column | kind | type | unit | meaning |\n|---|---|---|---|---|\n";
    for (const ColumnSpec& c : runColumnSpecs()) {
        if (c.kind == ColumnKind::Parameter && c.name != "run" && c.name != "label" && c.name != "sweep" &&
            c.name != "config_hash")
            continue;
        if (c.name == "experiment_output") continue;  // a config key, recorded as context
        out += "| `" + c.name + "` | " + columnKindName(c.kind) + " | " + columnValueType(c) + " | " + c.unit + " | " + c.help +
               " |\n";
    }
    return out;
}

const char* columnValueType(const ColumnSpec& column) {
    switch (column.type == ColumnType::Inferred ? inferredType(column) : column.type) {
        case ColumnType::Integer: return "integer";
        case ColumnType::Boolean: return "boolean";
        case ColumnType::Text: return "text";
        case ColumnType::Number:
        case ColumnType::Inferred: break;
    }
    return "number";
}

std::string columnsCsv() {
    std::vector<Row> rows;
    for (const ColumnSpec& c : runColumnSpecs()) {
        std::string when;
        for (const std::string& w : c.appliesWhen) when += (when.empty() ? "" : " and ") + w;
        rows.push_back({{"column", c.name}, {"kind", columnKindName(c.kind)}, {"type", columnValueType(c)}, {"unit", c.unit},
                        {"since_schema", std::to_string(c.since)}, {"written_when", when}, {"meaning", c.help}});
    }
    return csvText("columns.csv", {"column", "kind", "type", "unit", "since_schema", "written_when", "meaning"}, rows);
}

int schemaVersion(const Json& context) {
    const auto it = context.find("schema_version");
    return it != context.end() && it->is_number_integer() ? it->get<int>() : 1;
}

std::vector<Row> readRunsCsv(const std::string& path, int* schema) {
    return parseRunsCsv(readInputFile(path, kMaxResultsFileBytes, "CSV file"), path, schema);
}

namespace {

// Before results schema 6 a 3-vector key was one "[x y z]" cell (formatValue); its three numbers
// are split into the key's three columns here, so every reader sees today's columns. Returns
// whether the file had such a cell's column.
bool splitVectorCells(std::set<std::string>& header, std::vector<Row>& rows, const std::string& path) {
    bool found = false;
    for (const KeySpec& key : configSchema()) {
        const std::vector<std::string> columns = keyColumns(key);
        const std::string old = paramColumn(key.name);
        if (columns.size() != 3 || !header.count(old)) continue;
        found = true;
        header.erase(old);
        header.insert(columns.begin(), columns.end());
        for (std::size_t r = 0; r < rows.size(); ++r) {
            const std::string cell = rows[r][old];
            rows[r].erase(old);
            std::string parts[3];
            if (!cell.empty()) {
                std::istringstream in(cell.front() == '[' && cell.back() == ']' ? cell.substr(1, cell.size() - 2) : "");
                std::string extra;
                const auto number = [](const std::string& t) { return !std::isnan(cellNumber(t)); };
                if (!(in >> parts[0] >> parts[1] >> parts[2]) || (in >> extra) || !number(parts[0]) || !number(parts[1]) ||
                    !number(parts[2]))
                    throw Error(path + ": row " + std::to_string(r + 1) + ", column " + old + ": '" + cell +
                                "' is not a 3-vector \"[x y z]\"");
            }
            for (int a = 0; a < 3; ++a) rows[r][columns[a]] = parts[a];
        }
    }
    return found;
}

}  // namespace

std::vector<Row> parseRunsCsv(const std::string& text, const std::string& path, int* schemaOut) {
    std::vector<Row> rows = parseCsv(text, path);
    if (schemaOut) *schemaOut = kSchemaVersion;
    const std::vector<std::string> declared = runColumns();
    const std::set<std::string> declaredSet(declared.begin(), declared.end());
    // The header: the first row's columns, or (a file of no rows) its first line's names.
    std::set<std::string> header;
    if (!rows.empty()) {
        for (const auto& [c, value] : rows[0]) header.insert(c);
    } else {
        std::string line = text.substr(0, text.find('\n')), name;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        std::istringstream names(line);
        while (std::getline(names, name, ',')) header.insert(name);
    }
    const bool vectorsInOneCell = splitVectorCells(header, rows, path);
    if (!header.empty()) {
        // A column a run of this file would have written must be there; a method's own column may
        // be absent when no row ran that method (with no rows: only the columns every run writes).
        auto needed = [&](const ColumnSpec& c) {
            if (rows.empty()) return c.appliesWhen.empty();
            return std::any_of(rows.begin(), rows.end(), [&](const Row& row) {
                return conditionsHold(c.appliesWhen, [&](const std::string& key) {
                    const auto it = row.find(paramColumn(key));
                    return it != row.end() ? std::optional<std::string>(it->second) : std::nullopt;
                });
            });
        };
        // The file's schema: the newest whose every needed column is there. A file of an older
        // schema has none of a later one's columns; one with some of them was cut or edited.
        int schema = kSchemaVersion;
        for (int v = 1; v <= kSchemaVersion && schema == kSchemaVersion; ++v)
            for (const ColumnSpec& c : runColumnSpecs())
                if (c.since == v && !header.count(c.name) && needed(c)) {
                    schema = v - 1;
                    break;
                }
        // Schema 6 added no column: it split the 3-vector cells.
        if (vectorsInOneCell) schema = std::min(schema, 5);
        std::string missing, unknown;
        bool laterPresent = false;
        for (const ColumnSpec& c : runColumnSpecs()) {
            if (c.since > schema && header.count(c.name)) laterPresent = true;
            if (!header.count(c.name) && needed(c) && (c.since <= schema + 1))
                missing += (missing.empty() ? "" : ", ") + c.name;
        }
        for (const std::string& c : header)
            if (!declaredSet.count(c)) unknown += (unknown.empty() ? "" : ", ") + c;
        if (schema < 1 || laterPresent)
            throw Error(path + ": missing column(s) " + missing + " (of results schema " + std::to_string(schema + 1) +
                        "; the file has other columns of it or none of schema 1: cut, edited, or written by another rtbench?)");
        if (schemaOut) *schemaOut = schema;
        if (!unknown.empty()) throw Error(path + ": unknown column(s) " + unknown);
    }
    std::set<std::string> runs;
    for (std::size_t r = 0; r < rows.size(); ++r) {
        const std::string& run = rows[r].at("run");
        if (run.empty())
            throw Error(path + ": row " + std::to_string(r + 1) + " has no run number");
        if (!runs.insert(run).second)
            throw Error(path + ": run " + run + " appears more than once");
    }
    return rows;
}

}  // namespace rtbench
