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
#include "retime.h"
#include "run_columns.h"
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
    // A part's typed columns (schema/column.h), in their order.
    void append(const std::vector<ColumnSpec>& columns) { specs.insert(specs.end(), columns.begin(), columns.end()); }
    // A structure's, ray type's or strategy's own columns, written only by its runs (`typeKey` =
    // `name`). A column several methods write (rays_cut_short, the lane model's lanes_model_*:
    // strategies/branching/branching_strategy.h) is listed by each: its condition names them all.
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
    s.append(runColumnsDeclared().identity.specs());  // harness/run_columns.h
}

// Scene, rays, the shading passes that made them, and the structure.
void addSceneColumns(ColumnList& s) {
    s.append(sceneInputColumns());          // harness/run_inputs.cpp
    s.append(batchColumns());               // harness/run_pipeline.cpp
    s.append(shadingColumns());             // rays/workload.cpp
    s.append(cameraAndStructureColumns());  // harness/run_pipeline.cpp
}

// Time: the kernel's and Embree's on the same rays (every sample is in samples.csv).
void addTimingColumns(ColumnList& s) {
    s.append(timingColumns(TimingColumnPart::Methods));  // harness/run_metrics.cpp
    s.specs.push_back(embreeRaysColumn());  // harness/run_pipeline.cpp
    s.append(embreeColumns());  // harness/run_inputs.cpp
    s.append(timingColumns(TimingColumnPart::Ratio));
    s.append(timingColumns(TimingColumnPart::Rounds));
    s.specs.push_back(retimedColumn().spec());  // harness/retime.cpp
    s.append(timingColumns(TimingColumnPart::Machine));
}

// Agreement with Embree (a second view of accuracy: depends on Embree's floating-point path),
// accuracy against the exact reference (harness/exact_reference.h: the kernels' counts are
// deterministic, Embree's depend on its ISA path), and the image against the exact render.
void addAccuracyColumns(ColumnList& s) {
    s.append(agreementColumns());  // harness/run_pipeline.cpp
    s.append(exactSampleColumns());  // harness/run_pipeline.cpp
    s.append(exactColumns(false));  // harness/run_metrics.cpp: the kernel's, then Embree's
    s.append(exactColumns(true));
    s.append(imageColumns());
}

// Self-checks (a mismatch fails the run), and the run's wall time.
void addSelfCheckColumns(ColumnList& s) {
    s.append(selfCheckColumns());  // harness/run_pipeline.cpp
    s.specs.push_back(runColumnsDeclared().wallSeconds.spec());
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
