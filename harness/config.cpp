#include "config.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "embree_config.h"
#include "methods/registry.h"
#include "output_folder.h"
#include "structures/error.h"

namespace rtbench {

namespace {

std::string join(const std::vector<std::string>& items, const std::string& sep = ", ") {
    std::string out;
    for (const std::string& s : items) out += (out.empty() ? "" : sep) + s;
    return out;
}

const char* typeName(ValueType t) {
    switch (t) {
        case ValueType::Int: return "an integer";
        case ValueType::Float: return "a number";
        case ValueType::String: return "a string";
        case ValueType::Bool: return "true or false";
        case ValueType::Int3: return "an array of 3 integers";
        case ValueType::Float3: return "an array of 3 numbers";
    }
    return "?";
}

// intersection.vertex_bits: packed to 1..16 bits per axis, or 32 (float).
std::vector<std::string> vertexBitsChoices() {
    std::vector<std::string> choices;
    for (int bits = 1; bits <= 16; ++bits) choices.push_back(std::to_string(bits));
    choices.push_back("32");
    return choices;
}

std::string where(const std::string& file, const toml::source_region& src) {
    if (src.begin.line == 0) return file;
    return file + ":" + std::to_string(src.begin.line);
}

}  // namespace

const std::vector<KeySpec>& configSchema() {
    static const std::vector<KeySpec> schema = [] {
        std::vector<KeySpec> s;
        auto add = [&](KeySpec k) { s.push_back(std::move(k)); };
        add({"experiment.name", ValueType::String, "experiment name, a plain folder name; results go to <output>/<name>/", {}, true, -1e300, 1e300, {}, {},
             [](const std::string& name) { experimentFolder("", name); }});
        add({"experiment.output", ValueType::String, "output folder (relative to the working directory)", std::string("out")});
        add({"experiment.repetitions", ValueType::Int, "timed repetitions per run (median reported)", std::int64_t(5), false, 1, 1000});
        add({"experiment.warmups", ValueType::Int, "untimed warm-up dispatches before timing", std::int64_t(1), false, 0, 100});
        add({"scene.source", ValueType::String, "mesh file (.off/.obj/.ply/.stl, relative to the config), scene description (.toml, relative to the config: meshes with transforms and seeded scatters, see structures/scene_description.h), cgal:NAME, or procedural:christen_a|christen_b|christen_b_thesis|closed_box|icosphere|tetrahedron", {}, true});
        add({"scene.scale", ValueType::Float, "uniform scale applied to every vertex, in float: v * scale + translate (camera.position and camera.look_at move with the scene)", 1.0, false, 1e-30, 1e30});
        add({"scene.translate", ValueType::Float3, "translation applied after scene.scale, in float (stability sweeps move a scene away from the origin)", std::array<double, 3>{0, 0, 0}});
        add({"scene.simplify_ratio", ValueType::Float, "simplify the scene by edge collapse (CGAL Surface_mesh_simplification, Lindstrom-Turk) to at most this fraction of its triangles; every method traces the simplified scene, the exact reference the full one", {}, false, 1e-9, 1, {}, {}, {}, "scene simplification"});
        add({"scene.simplify_triangles", ValueType::Int, "simplify the scene by edge collapse to exactly this many triangles (else the run fails saying why); as scene.simplify_ratio", {}, false, 1, 4294967295.0, {}, {}, {}, "scene simplification"});
        add({"camera.width", ValueType::Int, "image width in pixels", std::int64_t(1024), false, 1, 16384});
        add({"camera.height", ValueType::Int, "image height in pixels", std::int64_t(1024), false, 1, 16384});
        add({"camera.position", ValueType::Float3, "eye position (default: the procedural scene's own viewpoint, else fitted to the scene bounds)", {}});
        add({"camera.look_at", ValueType::Float3, "point looked at (default: the scene box centre)", {}});
        add({"camera.up", ValueType::Float3, "up vector", std::array<double, 3>{0, 1, 0}});
        add({"camera.fov_deg", ValueType::Float, "vertical field of view in degrees", 45.0, false, 1, 179});
        // Each structure's and strategy's own keys, read only when it is chosen (methods/registry.cpp).
        auto addMethodKeys = [&](const std::string& typeKey, const std::string& name, const std::vector<KeySpec>& keys) {
            for (KeySpec k : keys) {
                k.appliesWhen.insert(k.appliesWhen.begin(), typeKey + "=" + name);
                add(std::move(k));
            }
        };
        std::vector<std::string> structures, strategies;
        std::string structureHelp = "acceleration structure:", strategyHelp = "how the GPU runs the traversal:";
        for (const StructureType* t : structureTypes()) {
            structures.push_back(t->name);
            structureHelp += " " + t->name + " (" + t->help + ");";
        }
        for (const StrategyType* t : strategyTypes()) {
            strategies.push_back(t->name);
            strategyHelp += " " + t->name + " (" + t->help + ");";
        }
        structureHelp.pop_back();
        strategyHelp.pop_back();
        add({"structure.type", ValueType::String, structureHelp, structures.front(), false, -1e300, 1e300, structures});
        for (const StructureType* t : structureTypes()) addMethodKeys("structure.type", t->name, t->keys);
        add({"strategy.type", ValueType::String, strategyHelp, strategies.front(), false, -1e300, 1e300, strategies});
        add({"strategy.workgroup_size", ValueType::Int, "invocations per workgroup (specialization constant)", std::int64_t(64), false, 1, 1024});
        for (const StrategyType* t : strategyTypes()) addMethodKeys("strategy.type", t->name, t->keys);
        add({"intersection.test", ValueType::String, "ray-triangle test of every structure and strategy, on the GPU and in the CPU reference: moller_trumbore (Moller & Trumbore 1997) or watertight (Woop, Benthin & Wald 2013: no ray slips between triangles sharing an edge)", std::string("moller_trumbore"), false, -1e300, 1e300, {"moller_trumbore", "watertight"}});
        add({"intersection.vertex_bits", ValueType::Int, "32: float vertices; 1..16: every vertex snapped to a lattice of 2^bits points per axis over the scene's box and stored packed (20 bytes a triangle instead of 48); every method traces the snapped scene, the exact reference the original", std::int64_t(32), false, 1, 32, vertexBitsChoices()});
        add({"baseline.embree_config", ValueType::String, "Embree device config string, e.g. \"isa=avx2\" (keys isa, max_isa, threads, start_threads, set_affinity, verbose)", std::string(""), false, -1e300, 1e300, {}, {}, checkEmbreeConfig});
        add({"accuracy.exact_rays", ValueType::Int, "rays checked against the exact reference (CGAL, exact arithmetic): an even stride over the image from ray 0; 0 = every ray", std::int64_t(1048576), false, 0, 4294967295.0});
        add({"device.name", ValueType::String, "\"auto\" (discrete GPU, else lavapipe) or a substring of the device name", std::string("auto")});
        add({"device.validation", ValueType::Bool, "enable the Vulkan validation layer (a run fails on any message)", false});
        add({"output.images", ValueType::Bool, "write PNGs (needs OpenImageIO; else hit records are kept)", true});
        add({"output.hit_records", ValueType::Bool, "keep per-ray hit records (<run>.hits) for `rtbench images`", false});
        return s;
    }();
    return schema;
}


namespace {

// Converts one TOML node (scalar or 3-array) to a value of the spec's type, or throws.
ConfigValue convert(const std::string& file, const KeySpec& spec, const toml::node& node) {
    const std::string at = where(file, node.source()) + ": key '" + spec.name + "': ";
    auto checkRange = [&](double v) {
        if (!(v >= spec.min && v <= spec.max)) {
            std::ostringstream s;
            s << at << "value " << v << " is out of range [" << spec.min << ", " << spec.max << "]";
            throw Error(s.str());
        }
    };
    auto wrongType = [&]() -> Error {
        return Error(at + "expected " + typeName(spec.type) + " (or a list of them to sweep)");
    };
    switch (spec.type) {
        case ValueType::Int: {
            if (!node.is_integer()) throw wrongType();
            const std::int64_t v = node.as_integer()->get();
            checkRange(static_cast<double>(v));
            if (!spec.choices.empty() &&
                std::find(spec.choices.begin(), spec.choices.end(), std::to_string(v)) == spec.choices.end())
                throw Error(at + "value " + std::to_string(v) + " is not allowed (allowed: " + join(spec.choices) + ")");
            return v;
        }
        case ValueType::Float: {
            if (!node.is_number()) throw wrongType();
            const double v = node.value<double>().value();
            if (!std::isfinite(v)) throw Error(at + "value must be finite");
            checkRange(v);
            return v;
        }
        case ValueType::String: {
            if (!node.is_string()) throw wrongType();
            const std::string v = node.as_string()->get();
            if (!spec.choices.empty() &&
                std::find(spec.choices.begin(), spec.choices.end(), v) == spec.choices.end())
                throw Error(at + "'" + v + "' is not allowed (allowed: " + join(spec.choices) + ")");
            if (spec.check) {
                try {
                    spec.check(v);
                } catch (const Error& e) {
                    throw Error(at + e.what());
                }
            }
            return v;
        }
        case ValueType::Bool:
            if (!node.is_boolean()) throw wrongType();
            return node.as_boolean()->get();
        case ValueType::Int3:
        case ValueType::Float3: {
            const toml::array* a = node.as_array();
            if (!a || a->size() != 3) throw wrongType();
            std::array<double, 3> v{};
            for (std::size_t i = 0; i < 3; ++i) {
                const toml::node& e = *a->get(i);
                if (spec.type == ValueType::Int3 ? !e.is_integer() : !e.is_number()) throw wrongType();
                v[i] = e.value<double>().value();
                if (!std::isfinite(v[i])) throw Error(at + "value must be finite");
                checkRange(v[i]);
            }
            return v;
        }
    }
    throw wrongType();
}

// A list-valued node sweeps: for 3-vectors a list of 3-arrays, for scalars a list of scalars.
bool isSweep(const KeySpec& spec, const toml::node& node) {
    const toml::array* a = node.as_array();
    if (!a) return false;
    if (spec.type == ValueType::Int3 || spec.type == ValueType::Float3)
        return !a->empty() && a->get(0)->is_array();
    return true;
}

}  // namespace

ExperimentPlan loadExperiment(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw Error(path + ": cannot open config file");
    std::ostringstream text;
    text << in.rdbuf();
    return loadExperimentText(text.str(), path, std::filesystem::absolute(path).parent_path().string());
}

ExperimentPlan loadExperimentText(const std::string& configText, const std::string& path, const std::string& configDir) {
    ExperimentPlan plan;
    plan.configPath = path;
    plan.configText = configText;
    plan.configDir = configDir;

    toml::table root;
    try {
        root = toml::parse(plan.configText, path);
    } catch (const toml::parse_error& e) {
        throw Error(where(path, e.source()) + ": TOML syntax error: " + std::string(e.description()));
    }

    const std::vector<KeySpec>& schema = configSchema();
    std::map<std::string, std::vector<std::string>> sections;  // section -> keys
    std::vector<std::string> sectionOrder;
    for (const KeySpec& k : schema) {
        const std::string section = k.name.substr(0, k.name.find('.'));
        if (!sections.count(section)) sectionOrder.push_back(section);
        sections[section].push_back(k.name.substr(k.name.find('.') + 1));
    }
    using Given = std::map<std::string, const toml::node*>;

    // Unknown sections and keys are errors: a typo must not silently fall back to a default.
    auto readSection = [&](const toml::key& sectionKey, const toml::node& sectionNode, Given& given) {
        const std::string section(sectionKey.str());
        if (!sections.count(section))
            throw Error(where(path, sectionKey.source()) + ": unknown section [" + section + "] (allowed: " +
                        join(sectionOrder) + ", sweep)");
        const toml::table* table = sectionNode.as_table();
        if (!table)
            throw Error(where(path, sectionKey.source()) + ": '" + section + "' must be a table ([" + section + "])");
        for (auto&& [key, node] : *table) {
            const std::string name(key.str());
            const auto& allowed = sections[section];
            if (std::find(allowed.begin(), allowed.end(), name) == allowed.end())
                throw Error(where(path, key.source()) + ": unknown key '" + section + "." + name + "' (allowed in [" +
                            section + "]: " + join(allowed) + ")");
            given[section + "." + name] = &node;
        }
    };
    Given base;
    struct Sweep {
        std::string name;
        Given overrides;
        // Skip rules: a run matching every "section.key=value" of one rule is left out.
        std::vector<std::vector<std::pair<std::string, std::string>>> skip;
        std::string at;  // file:line of the [[sweep]] table
    };
    std::vector<Sweep> sweeps;
    for (auto&& [sectionKey, sectionNode] : root) {
        if (sectionKey.str() != "sweep") {
            readSection(sectionKey, sectionNode, base);
            continue;
        }
        const toml::array* list = sectionNode.as_array();
        if (!list || !list->is_array_of_tables())
            throw Error(where(path, sectionKey.source()) + ": 'sweep' must be an array of tables ([[sweep]])");
        for (const toml::node& element : *list) {
            Sweep sweep;
            sweep.at = where(path, element.source());
            for (auto&& [key, node] : *element.as_table()) {
                if (key.str() == "name") {
                    if (!node.is_string())
                        throw Error(where(path, key.source()) + ": key 'sweep.name': expected a string");
                    sweep.name = node.as_string()->get();
                } else if (key.str() == "skip") {
                    const toml::array* rules = node.as_array();
                    if (!rules) throw Error(where(path, key.source()) + ": key 'sweep.skip': expected a list of strings");
                    for (const toml::node& rule : *rules) {
                        if (!rule.is_string())
                            throw Error(where(path, rule.source()) + ": key 'sweep.skip': expected strings such as "
                                        "\"strategy.traverse_steps_per_pass=1 strategy.suppress_finished_reads=true\"");
                        std::vector<std::pair<std::string, std::string>> conditions;
                        std::istringstream words(rule.as_string()->get());
                        std::string word;
                        while (words >> word) {
                            const std::size_t eq = word.find('=');
                            const std::string name = word.substr(0, eq);
                            if (eq == std::string::npos ||
                                std::none_of(schema.begin(), schema.end(), [&](const KeySpec& k) { return k.name == name; }))
                                throw Error(where(path, rule.source()) + ": key 'sweep.skip': '" + word +
                                            "' is not section.key=value for a known key");
                            conditions.emplace_back(name, word.substr(eq + 1));
                        }
                        sweep.skip.push_back(std::move(conditions));
                    }
                } else {
                    readSection(key, node, sweep.overrides);
                }
            }
            sweeps.push_back(std::move(sweep));
        }
    }
    if (sweeps.empty()) sweeps.push_back(Sweep{});

    // Alternative keys by group (KeySpec::group), in schema order.
    std::map<std::string, std::vector<std::string>> groups;
    for (const KeySpec& spec : schema)
        if (!spec.group.empty()) groups[spec.group].push_back(spec.name);
    std::map<std::string, const toml::node*> unread;  // given keys no run has read yet
    std::set<std::string> seen;                        // canonical runs, to drop duplicates
    for (const Sweep& sweep : sweeps) {
        const std::string& sweepName = sweep.name;
        const Given& overrides = sweep.overrides;
        // A sweep that gives one key of a group replaces the base's choice in that group.
        Given given = base;
        for (const auto& [group, keys] : groups)
            if (std::any_of(keys.begin(), keys.end(), [&](const std::string& k) { return overrides.count(k); }))
                for (const std::string& k : keys) given.erase(k);
        for (const auto& [key, node] : overrides) given[key] = node;
        for (const auto& [key, node] : given) unread.emplace(key, node);

        std::set<std::string> groupsGiven;
        for (const auto& [group, keys] : groups) {
            std::vector<std::string> inGroup;
            for (const std::string& k : keys)
                if (given.count(k)) inGroup.push_back(k);
            if (inGroup.size() > 1)
                throw Error(where(path, given[inGroup[1]]->source()) + ": keys " + join(inGroup, " and ") +
                            " both set the " + group + "; give exactly one");
            if (!inGroup.empty()) groupsGiven.insert(group);
        }

        // Each key: a single value, a default, or a list of values (an axis of the sweep).
        std::vector<std::pair<std::string, std::vector<ConfigValue>>> axes;
        for (const KeySpec& spec : schema) {
            auto it = given.find(spec.name);
            std::vector<ConfigValue> values;
            if (it == given.end()) {
                if (spec.required)
                    throw Error(path + ": missing required key '" + spec.name + "' (" + spec.help + ")");
                if (spec.defaultValue) values.push_back(*spec.defaultValue);
                if (spec.groupDefault && !groupsGiven.count(spec.group)) values.push_back(*spec.groupDefault);
            } else if (isSweep(spec, *it->second)) {
                const toml::array& list = *it->second->as_array();
                if (list.empty())
                    throw Error(where(path, it->second->source()) + ": key '" + spec.name + "': an empty list sweeps nothing");
                for (const toml::node& element : list) values.push_back(convert(path, spec, element));
            } else {
                values.push_back(convert(path, spec, *it->second));
            }
            if (!values.empty()) axes.emplace_back(spec.name, std::move(values));
        }

        // Cartesian product, the last axis varying fastest; keys a run does not read are dropped.
        std::vector<std::string> swept;
        std::size_t total = 1;
        for (const auto& [key, values] : axes) {
            if (values.size() > 1) swept.push_back(key);
            total *= values.size();
            if (total > 100000) throw Error(path + ": the sweep expands to over 100000 runs");
        }
        std::size_t skippedRuns = 0;
        for (std::size_t r = 0; r < total; ++r) {
            RunConfig run;
            run.sweep = sweepName;
            std::size_t rest = r;
            for (auto it = axes.rbegin(); it != axes.rend(); ++it) {
                run.values[it->first] = it->second[rest % it->second.size()];
                rest /= it->second.size();
            }
            for (const KeySpec& spec : schema) {
                const bool applies = conditionsHold(spec.appliesWhen, [&](const std::string& key) {
                    return run.has(key) ? std::optional<std::string>(formatValue(run.values.at(key))) : std::nullopt;
                });
                if (!applies) run.values.erase(spec.name);
            }
            const bool skipped = std::any_of(sweep.skip.begin(), sweep.skip.end(), [&](const auto& rule) {
                return std::all_of(rule.begin(), rule.end(), [&](const auto& condition) {
                    return run.has(condition.first) && formatValue(run.values.at(condition.first)) == condition.second;
                });
            });
            if (skipped) {
                ++skippedRuns;
                continue;
            }
            for (const auto& [key, value] : run.values) unread.erase(key);
            for (const std::string& key : swept)
                if (run.has(key)) run.sweptKeys.push_back(key);
            if (!seen.insert(sweepName + "|" + run.canonical()).second) continue;
            run.index = plan.runs.size();
            plan.runs.push_back(std::move(run));
        }
        if (skippedRuns == total)
            throw Error(sweep.at + ": every one of the " + std::to_string(total) + " runs of sweep '" + sweepName +
                        "' matches a skip rule: the sweep runs nothing");
    }
    if (!unread.empty()) {
        const auto& [key, node] = *unread.begin();
        const KeySpec& spec = *std::find_if(schema.begin(), schema.end(), [&](const KeySpec& k) { return k.name == key; });
        throw Error(where(path, node->source()) + ": key '" + key + "' is never read: it applies only when " +
                    join(spec.appliesWhen, " and "));
    }
    return plan;
}

void overrideEmbreeConfig(ExperimentPlan& plan, const std::string& embreeConfig) {
    try {
        checkEmbreeConfig(embreeConfig);
    } catch (const Error& e) {
        throw Error("--embree-config: " + std::string(e.what()));
    }
    for (RunConfig& run : plan.runs) run.values["baseline.embree_config"] = embreeConfig;
}

}  // namespace rtbench
