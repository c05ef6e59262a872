#include "config.h"

#include <toml++/toml.h>

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "embree_config.h"
#include "methods/cache/cache_replay.h"
#include "methods/registry.h"
#include "core/text.h"
#include "rays/registry.h"
#include "output_folder.h"
#include "core/error.h"
#include "core/input_file.h"
#include "scene/mesh_io.h"

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
    if (src.path && src.path->rfind("--set ", 0) == 0) return *src.path;  // a command-line setting
    if (src.begin.line == 0) return file;
    return file + ":" + std::to_string(src.begin.line);
}

// The shortest decimal that reads back as v (179.9999 stays 179.9999, not "180").
std::string shortest(double v) {
    char text[32];
    const auto end = std::to_chars(text, text + sizeof text, v).ptr;
    return std::string(text, end);
}

}  // namespace

std::string keyTypeText(const KeySpec& key) {
    std::string text = typeName(key.type);
    const bool numeric = key.type != ValueType::String && key.type != ValueType::Bool;
    const bool integer = key.type == ValueType::Int || key.type == ValueType::Int3;
    auto bound = [&](double v) { return integer ? std::to_string(std::int64_t(v)) : formatValue(ConfigValue(v)); };
    if (numeric && (key.min > -1e300 || key.max < 1e300))
        text += (key.type == ValueType::Int3 || key.type == ValueType::Float3 ? ", each in [" : " in [") +
                (key.min > -1e300 ? bound(key.min) : std::string("-inf")) + ", " +
                (key.max < 1e300 ? bound(key.max) : std::string("inf")) + "]";
    if (!key.choices.empty()) text += ": one of " + join(key.choices);
    return text;
}

namespace {

// The config keys as they are declared, in their order.
struct KeyList {
    std::vector<KeySpec> specs;
    KeySpec& add(KeySpec k) { return specs.emplace_back(std::move(k)); }
    // A structure's, strategy's or ray type's own keys, read only when `typeKey` = `name`. A key
    // two types read (light.position: shadow and whitted rays) is declared by each and applies to both.
    void addMethod(const std::string& typeKey, const std::string& name, const std::vector<KeySpec>& keys) {
        for (KeySpec k : keys) {
            const auto same = std::find_if(specs.begin(), specs.end(), [&](const KeySpec& e) { return e.name == k.name; });
            if (same != specs.end() && !same->appliesWhen.empty() && same->appliesWhen.front().rfind(typeKey + "=", 0) == 0) {
                same->appliesWhen.front() += "|" + name;
                continue;
            }
            k.appliesWhen.insert(k.appliesWhen.begin(), typeKey + "=" + name);
            add(std::move(k));
        }
    }
};

// Where the results go, and how the runs are timed.
void addExperimentKeys(KeyList& s) {
    s.add({"experiment.name", ValueType::String, "experiment name, a plain folder name; results go to <output>/<name>/", {}, true, -1e300, 1e300, {}, {},
         [](const std::string& name) { experimentFolder("", name); }});
    s.add({"experiment.output", ValueType::String, "output folder (relative to the working directory)", std::string("out")});
    for (KeySpec& k : s.specs) k.sweepable = false;  // the two keys above place the results
    s.add({"experiment.repetitions", ValueType::Int, "timed repetitions of each method per run (the minimum, with experiment.target_ci)", std::int64_t(5), false, 1, 1000});
    s.add({"experiment.warmups", ValueType::Int, "untimed warm-up repetitions of each timed method (kernel, Embree) before its first round", std::int64_t(1), false, 0, 100});
    // Timing in rounds, adaptive repetitions and the noise guard (harness/timing_rounds.h).
    auto timingKey = [&](KeySpec k) {
        k.since = 5;
        s.add(std::move(k));
    };
    timingKey({"experiment.order", ValueType::String, "run: each run timed whole, one after another; interleaved: every run prepared first, then timed one round at a time across the sweep (round r of every run before round r + 1 of any), so runs compared in one table were timed under the same conditions; every run keeps its device buffers until the sweep's timing ends, and a row is written only when its run is finished", std::string("run"), false, -1e300, 1e300, {"run", "interleaved"}});
    s.specs.back().sweepable = false;  // one order for the whole sweep
    timingKey({"experiment.rounds", ValueType::Int, "the repetitions are split into this many rounds, each timing the kernel, then Embree rtcIntersect1, then rtcIntersect16, so that drift hits all of them (at most one round per repetition)", std::int64_t(5), false, 1, 1000});
    timingKey({"experiment.target_ci", ValueType::Float, "adaptive repetitions: after experiment.repetitions, add rounds until the 95% interval of every median (order statistics: 6 repetitions or more; kernel, Embree 1 and 16) is within +- this fraction of it, or experiment.max_repetitions or experiment.time_budget_s is reached (0: a fixed count)", 0.0, false, 0, 1});
    timingKey({"experiment.max_repetitions", ValueType::Int, "adaptive repetitions: at most this many of each method", std::int64_t(200), false, 1, 100000});
    timingKey({"experiment.time_budget_s", ValueType::Float, "adaptive repetitions: stop adding rounds once a run's timing has taken this long", 30.0, false, 0, 1e6});
    timingKey({"experiment.noise_cv", ValueType::Float, "noise guard, for a method with 2 to 5 repetitions (too few for an interval of the median): a timing_warning when its coefficient of variation exceeds this", 0.05, false, 0, 1e3});
    {
        KeySpec ci{"experiment.noise_ci", ValueType::Float, "noise guard, for a method with 6 repetitions or more: a timing_warning when the 95% interval of its median (order statistics) is wider than +- this fraction of the median (half the interval's width over the median)", 0.05, false, 0, 1e3};
        ci.since = 28;
        s.add(std::move(ci));
    }
    {
        KeySpec rounds{"experiment.build_rounds", ValueType::Int, "build the structure and Embree's BVH of the same triangles this many times more, alternately, and record their medians and their ratio with its interval (build_ratio_vs_embree; 7 rounds or more for the interval); 0: only the run's own build of each (structure_build_ms, embree_build_ms)", std::int64_t(0), false, 0, 1000};
        rounds.since = 27;
        s.add(std::move(rounds));
    }
    timingKey({"experiment.noise_other_cpu", ValueType::Float, "noise guard: a timing_warning when other processes took more than this fraction of the machine's CPU time while the run ran", 0.1, false, 0, 1});
}

// The scene and the camera.
void addSceneKeys(KeyList& s) {
    s.add({"scene.source", ValueType::String, "mesh file (.off/.obj/.ply/.stl, relative to the config), scene description (.toml, relative to the config: meshes with transforms and seeded scatters, see scene/scene_description.h), cgal:NAME, or procedural:christen_a|christen_b|christen_b_thesis|closed_box|icosphere|tetrahedron|forest|building", {}, true});
    s.add({"scene.scale", ValueType::Float, "uniform scale applied to every vertex, in float: v * scale + translate (camera.position and camera.look_at move with the scene)", 1.0, false, 1e-30, 1e30});
    s.add({"scene.translate", ValueType::Float3, "translation applied after scene.scale, in float (stability sweeps move a scene away from the origin)", std::array<double, 3>{0, 0, 0}});
    s.add({"scene.simplify_ratio", ValueType::Float, "simplify the scene by edge collapse (CGAL Surface_mesh_simplification, Lindstrom-Turk) to at most this fraction of its triangles; every method traces the simplified scene, the exact reference the full one", {}, false, 1e-9, 1, {}, {}, {}, "scene simplification"});
    s.add({"scene.simplify_triangles", ValueType::Int, "simplify the scene by edge collapse to exactly this many triangles (else the run fails saying why); as scene.simplify_ratio", {}, false, 1, 4294967295.0, {}, {}, {}, "scene simplification"});
    s.add({"camera.width", ValueType::Int, "image width in pixels", std::int64_t(1024), false, 1, 16384});
    s.add({"camera.height", ValueType::Int, "image height in pixels", std::int64_t(1024), false, 1, 16384});
    s.add({"camera.position", ValueType::Float3, "eye position (default: the procedural scene's own viewpoint, else fitted to the scene bounds)", {}});
    s.add({"camera.look_at", ValueType::Float3, "point looked at (default: the scene box centre)", {}});
    s.add({"camera.up", ValueType::Float3, "up vector", std::array<double, 3>{0, 1, 0}});
    s.add({"camera.fov_deg", ValueType::Float, "vertical field of view in degrees", 45.0, false, 1, 179});
    s.add({"camera.tile", ValueType::Int, "Purcell 2002 §5.3's tiled rendering: the method traces the camera rays in tiles of this many pixels square, tile after tile (0: row after row); width and height must be whole numbers of tiles. Multipass renders each tile to completion with strategy.batch_rays = tile x tile. The records, checks and images are the same; what changes is the order of memory references (cache.simulate) and the device's time. Embree traces row after row", std::int64_t(0), false, 0, 4096, {}, {"rays.type=primary"}});
    s.specs.back().since = 17;
}

// The structure and the strategy (each one's own keys, read only when it is chosen:
// methods/registry.cpp), and Purcell 2002 Fig. 9's cache.
void addMethodKeys(KeyList& s) {
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
    s.add({"structure.type", ValueType::String, structureHelp, structures.front(), false, -1e300, 1e300, structures});
    for (const StructureType* t : structureTypes()) s.addMethod("structure.type", t->name, t->keys);
    s.add({"strategy.type", ValueType::String, strategyHelp, strategies.front(), false, -1e300, 1e300, strategies});
    s.add({"strategy.workgroup_size", ValueType::Int, "invocations per workgroup (specialization constant)", std::int64_t(64), false, 1, 1024});
    for (const StrategyType* t : strategyTypes()) s.addMethod("strategy.type", t->name, t->keys);
    for (const KeySpec& k : cacheKeys()) s.add(k);  // Purcell 2002 Fig. 9's cache, for branching and multipass
}

// What the run traces (rays/registry.cpp), and each ray type's own keys.
void addRayKeys(KeyList& s) {
    std::vector<std::string> rayTypeNames;
    std::string rayTypeHelp = "the rays the run measures:";
    for (const RayType* t : rayTypes()) {
        rayTypeNames.push_back(t->name);
        rayTypeHelp += " " + t->name + " (" + t->help + ");";
    }
    rayTypeHelp.pop_back();
    s.add({"rays.type", ValueType::String, rayTypeHelp, rayTypeNames.front(), false, -1e300, 1e300, rayTypeNames});
    s.specs.back().since = 7;
    s.add({"rays.query", ValueType::String, "what the rays ask: own (the ray type's: any for shadow and ao, closest for the others), closest (the nearest hit: what a shadow ray costs without early termination) or any (the walk ends at its first hit)", std::string("own"), false, -1e300, 1e300, {"own", "closest", "any"}});
    s.specs.back().since = 7;
    for (const RayType* t : rayTypes()) s.addMethod("rays.type", t->name, t->keys);
}

// The ray-triangle test, Embree, the exact reference, the device and the output.
void addRunKeys(KeyList& s) {
    s.add({"intersection.test", ValueType::String, "ray-triangle test of every structure and strategy, on the GPU and in the CPU reference: moller_trumbore (Moller & Trumbore 1997) or watertight (Woop, Benthin & Wald 2013: no ray slips between triangles sharing an edge)", std::string("moller_trumbore"), false, -1e300, 1e300, {"moller_trumbore", "watertight"}});
    s.add({"intersection.division", ValueType::String, "how every kernel and CPU reference divides, both giving IEEE's correctly rounded float quotient bit for bit: double (the double quotient rounded to float: one double division, which consumer GPUs run at 1/64 rate) or integer (the device's own quotient corrected with 32-bit integer arithmetic, no double on the common path; slower than double on llvmpipe, where double division is the CPU's own: results/division); the plain strategy divides as the device does either way", std::string("double"), false, -1e300, 1e300, {"double", "integer"}});
    s.specs.back().since = 18;
    s.add({"intersection.vertex_bits", ValueType::Int, "32: float vertices; 1..16: every vertex snapped to a lattice of 2^bits points per axis over the scene's box and stored packed (20 bytes a triangle instead of 48); every method traces the snapped scene, the exact reference the original", std::int64_t(32), false, 1, 32, vertexBitsChoices()});
    s.add({"baseline.embree_config", ValueType::String, "Embree device config string, e.g. \"isa=avx2\" (keys isa, max_isa, threads, start_threads, set_affinity, verbose)", std::string(""), false, -1e300, 1e300, {}, {}, checkEmbreeConfig});
    s.add({"accuracy.exact_rays", ValueType::Int, "rays checked against the exact reference (CGAL, exact arithmetic): an even stride over the image from ray 0; 0 = every ray", std::int64_t(1048576), false, 0, 4294967295.0});
    s.add({"device.name", ValueType::String, "\"auto\" (discrete GPU, else lavapipe) or a substring of the device name or of its driver (\"Mesa 25\": the backports lavapipe when the loader sees it, VK_ADD_DRIVER_FILES)", std::string("auto")});
    s.add({"device.validation", ValueType::Bool, "enable the Vulkan validation layer (a run fails on any message) and fill each new device buffer with NaNs, so that a read of memory nothing wrote fails every time", false});
    s.add({"output.images", ValueType::Bool, "write PNGs (needs OpenImageIO; else hit records are kept)", true});
    {
        KeySpec exr{"output.exr", ValueType::Bool, "also write each run's shaded image as <run>-shaded.exr: the shades in float (a hit's |cos| between normal and ray, or the batch image's value; a miss 0), one channel Y, through OpenImageIO's OpenEXR writer", false};
        exr.appliesWhen = {"output.images=true"};
        exr.since = 10;
        s.add(std::move(exr));
    }
    s.add({"output.hit_records", ValueType::Bool, "keep per-ray hit records (<run>.hits) for `rtbench images`", false});
}

}  // namespace

const std::vector<KeySpec>& configSchema() {
    static const std::vector<KeySpec> schema = [] {
        KeyList s;
        addExperimentKeys(s);
        addSceneKeys(s);
        addMethodKeys(s);
        addRayKeys(s);
        addRunKeys(s);
        return s.specs;
    }();
    return schema;
}

const KeySpec& keySpec(const std::string& name) {
    static const std::map<std::string, const KeySpec*> byName = [] {
        std::map<std::string, const KeySpec*> m;
        for (const KeySpec& k : configSchema()) m[k.name] = &k;
        return m;
    }();
    const auto it = byName.find(name);
    if (it == byName.end()) throw Error("config key '" + name + "' is not declared (harness/config.cpp or a method's own keys)");
    return *it->second;
}


namespace {

// "; did you mean 'X'?" for the candidate nearest `name` when it is a likely typo of it (an edit
// distance of at most a third of its length, at least 1); "" when none is that near.
std::string didYouMean(const std::string& name, const std::vector<std::string>& candidates, const std::string& prefix = "") {
    const std::string* best = nullptr;
    std::size_t bestDistance = std::max<std::size_t>(1, name.size() / 3) + 1;
    for (const std::string& c : candidates)
        if (const std::size_t d = editDistance(name, c); d < bestDistance) {
            best = &c;
            bestDistance = d;
        }
    return best ? "; did you mean '" + prefix + *best + "'?" : "";
}

// Converts one TOML node (scalar or 3-array) to a value of the spec's type, or throws.
// `location` replaces the node's own (a value parsed out of a skip rule's text).
ConfigValue convert(const std::string& file, const KeySpec& spec, const toml::node& node,
                    const std::string& location = "") {
    const std::string at = (location.empty() ? where(file, node.source()) : location) + ": key '" + spec.name + "': ";
    auto checkRange = [&](double v) {
        if (!(v >= spec.min && v <= spec.max))
            throw Error(at + "value " + shortest(v) + " is out of range [" + shortest(spec.min) + ", " +
                        shortest(spec.max) + "]");
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
            refuseControlCharacters(at, v);
            if (!spec.choices.empty() &&
                std::find(spec.choices.begin(), spec.choices.end(), v) == spec.choices.end())
                throw Error(at + "'" + v + "' is not allowed (allowed: " + join(spec.choices) + ")" + didYouMean(v, spec.choices));
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

// A skip rule of a [[sweep]]: "key=value key=value"; a run matching every condition is left out.
// Values are typed as the key's own (30 = 30.0 = 30.000, 1e9 = 1000000000, [1, 0, 0]) and checked
// as the key would be (a choice not allowed, a bool given as 1, a range), so a rule cannot miss
// by spelling.
struct SkipRule {
    std::string text, at;  // as written, and its file:line
    KeyConditions conditions;
    // A run lacking a key (one its structure or strategy does not read) does not match.
    bool matches(const RunConfig& run) const { return runMatches(run, conditions); }
};

// Words split at spaces outside [...] and "...".
std::vector<std::string> ruleWords(const std::string& rule) {
    std::vector<std::string> words;
    std::string word;
    int depth = 0;
    bool quoted = false;
    for (char c : rule) {
        if (c == '"') quoted = !quoted;
        if (!quoted && c == '[') ++depth;
        if (!quoted && c == ']') --depth;
        if (!quoted && depth <= 0 && std::isspace(static_cast<unsigned char>(c))) {
            if (!word.empty()) words.push_back(std::move(word));
            word.clear();
            continue;
        }
        word += c;
    }
    if (!word.empty()) words.push_back(std::move(word));
    return words;
}

// `option` names what holds the rule in errors (the key sweep.skip; none for --filter).
SkipRule parseSkipRule(const std::string& path, const std::string& at, const std::string& text,
                       const std::vector<KeySpec>& schema, const std::string& option = "key 'sweep.skip': ") {
    SkipRule rule{text, at, {}};
    const std::string key = at + ": " + option;
    refuseControlCharacters(key, text);
    for (const std::string& word : ruleWords(text)) {
        const std::size_t eq = word.find('=');
        const std::string name = word.substr(0, eq);
        const auto spec = std::find_if(schema.begin(), schema.end(), [&](const KeySpec& k) { return k.name == name; });
        if (eq == std::string::npos || spec == schema.end())
            throw Error(key + "'" + word + "' is not section.key=value for a known key");
        std::string value = word.substr(eq + 1);
        const std::string valueAt = at + ": " + option + "in '" + word + "'";
        if (spec->type == ValueType::String) {
            // A bare word or a quoted string.
            if (value.size() >= 2 && value.front() == '"' && value.back() == '"') value = value.substr(1, value.size() - 2);
            rule.conditions.emplace_back(name, convert(path, *spec, toml::value<std::string>(value), valueAt));
            continue;
        }
        toml::table parsed;
        try {
            // One value, nothing after it (a '#' would start a comment that hides the rest).
            if (value.find_first_of("#\n") == std::string::npos) parsed = toml::parse("v = " + value);
        } catch (const toml::parse_error&) {
        }
        if (!parsed.contains("v"))
            throw Error(valueAt + ": key '" + name + "': '" + value + "' is not " + typeName(spec->type));
        rule.conditions.emplace_back(name, convert(path, *spec, *parsed.get("v"), valueAt));
    }
    if (rule.conditions.empty()) throw Error(key + "an empty rule");
    return rule;
}

// A list-valued node sweeps: for 3-vectors a list of 3-arrays, for scalars a list of scalars.
bool isSweep(const KeySpec& spec, const toml::node& node) {
    const toml::array* a = node.as_array();
    if (!a) return false;
    if (spec.type == ValueType::Int3 || spec.type == ValueType::Float3)
        return !a->empty() && a->get(0)->is_array();
    return true;
}

// One --set "section.key=value": the key checked against the schema (nearest names suggested), the
// value read as TOML (a list sweeps), or as a plain string where it is no TOML value (cgal:bunny00).
// The value's node, kept in `tables`, names "--set SETTING" as its source in every later error.
std::pair<std::string, const toml::node*> parseSetting(const std::string& setting, std::vector<toml::table>& tables,
                                                         const std::vector<KeySpec>& schema) {
    const std::string origin = "--set " + setting;
    const std::size_t eq = setting.find('=');
    if (eq == std::string::npos || eq == 0)
        throw Error(origin + ": expected section.key=value, e.g. --set structure.min_dim=[16,32]");
    const std::string key = setting.substr(0, eq), value = setting.substr(eq + 1);
    if (std::none_of(schema.begin(), schema.end(), [&](const KeySpec& k) { return k.name == key; })) {
        std::vector<std::string> names;
        for (const KeySpec& k : schema) names.push_back(k.name);
        throw Error(origin + ": unknown key '" + key + "' (nearest: " + join(nearestNames(key, names, 3)) +
                    "; rtbench keys lists them)");
    }
    toml::table parsed;
    try {
        parsed = toml::parse("v = " + value, origin);
    } catch (const toml::parse_error&) {
    }
    if (parsed.size() != 1 || !parsed.contains("v")) {  // no single TOML value: the text itself, as a string
        std::ostringstream quoted;
        quoted << toml::table{{"v", value}};
        parsed = toml::parse(quoted.str(), origin);
    }
    tables.push_back(std::move(parsed));
    return {key, tables.back().get("v")};
}

}  // namespace

KeyConditions parseKeyConditions(const std::string& at, const std::string& text) {
    return parseSkipRule("", at, text, configSchema(), "").conditions;
}

bool runMatches(const RunConfig& run, const KeyConditions& conditions) {
    return std::all_of(conditions.begin(), conditions.end(),
                       [&](const auto& c) { return run.has(c.first) && run.values.at(c.first) == c.second; });
}

ExperimentPlan loadExperiment(const std::string& path, const std::vector<std::string>& settings) {
    const std::string text = readInputFile(path, kMaxConfigBytes, "config file");
    return loadExperimentText(text, path, std::filesystem::absolute(path).parent_path().string(), settings);
}

namespace {

// A config's given keys, each with its TOML node (where errors point).
using Given = std::map<std::string, const toml::node*>;

// Every error of a file, reported at once (each file:line: key), not one per attempt.
struct ErrorList {
    std::vector<std::string> errors;
    void note(const std::string& error) {
        if (std::find(errors.begin(), errors.end(), error) == errors.end()) errors.push_back(error);
    }
    void throwIfAny(const std::string& path) const {
        if (errors.size() == 1) throw Error(errors.front());
        if (!errors.empty()) throw Error(std::to_string(errors.size()) + " errors in " + path + ":\n  " + join(errors, "\n  "));
    }
};

// The schema's keys by section ([experiment], [scene], ...), sections in schema order.
struct Sections {
    std::map<std::string, std::vector<std::string>> keys;
    std::vector<std::string> order;
    explicit Sections(const std::vector<KeySpec>& schema) {
        for (const KeySpec& k : schema) {
            const std::string section = k.name.substr(0, k.name.find('.'));
            if (!keys.count(section)) order.push_back(section);
            keys[section].push_back(k.name.substr(k.name.find('.') + 1));
        }
    }
};

struct Sweep {
    std::string name;
    Given overrides;
    // Skip rules: a run matching every "section.key=value" of one rule is left out.
    std::vector<SkipRule> skip;
    std::string at;  // file:line of the [[sweep]] table
};

// The file's base keys and its [[sweep]] tables (one empty sweep when it has none).
struct ConfigTables {
    Given base;
    std::vector<Sweep> sweeps;
};

toml::table parseToml(const std::string& text, const std::string& path) {
    try {
        return toml::parse(text, path);
    } catch (const toml::parse_error& e) {
        throw Error(where(path, e.source()) + ": TOML syntax error: " + std::string(e.description()));
    }
}

// One [section] into `given`. Unknown sections and keys are errors: a typo must not silently fall
// back to a default.
void readSection(const std::string& path, const Sections& sections, const toml::key& sectionKey, const toml::node& sectionNode,
                 Given& given, ErrorList& errors) {
    const std::string section(sectionKey.str());
    if (!sections.keys.count(section))
        throw Error(where(path, sectionKey.source()) + ": unknown section [" + section + "] (allowed: " +
                    join(sections.order) + ", sweep)");
    const toml::table* table = sectionNode.as_table();
    if (!table) throw Error(where(path, sectionKey.source()) + ": '" + section + "' must be a table ([" + section + "])");
    const std::vector<std::string>& allowed = sections.keys.at(section);
    for (auto&& [key, node] : *table) {
        const std::string name(key.str());
        if (std::find(allowed.begin(), allowed.end(), name) == allowed.end()) {
            errors.note(where(path, key.source()) + ": unknown key '" + section + "." + name + "' (allowed in [" + section +
                        "]: " + join(allowed) + ")" + didYouMean(name, allowed, section + "."));
            continue;
        }
        given[section + "." + name] = &node;
    }
}

// One [[sweep]] table: its name, skip rules and the sections it overrides.
Sweep readSweep(const std::string& path, const Sections& sections, const std::vector<KeySpec>& schema, const toml::node& element,
                ErrorList& errors) {
    Sweep sweep;
    sweep.at = where(path, element.source());
    for (auto&& [key, node] : *element.as_table()) {
        if (key.str() == "name") {
            if (!node.is_string()) throw Error(where(path, key.source()) + ": key 'sweep.name': expected a string");
            sweep.name = node.as_string()->get();
            refuseControlCharacters(where(path, key.source()) + ": key 'sweep.name': ", sweep.name);
        } else if (key.str() == "skip") {
            const toml::array* rules = node.as_array();
            if (!rules) throw Error(where(path, key.source()) + ": key 'sweep.skip': expected a list of strings");
            for (const toml::node& rule : *rules) {
                if (!rule.is_string())
                    throw Error(where(path, rule.source()) + ": key 'sweep.skip': expected strings such as "
                                "\"strategy.traverse_steps_per_pass=1 strategy.suppress_finished_reads=true\"");
                sweep.skip.push_back(parseSkipRule(path, where(path, rule.source()), rule.as_string()->get(), schema));
            }
        } else {
            try {
                readSection(path, sections, key, node, sweep.overrides, errors);
            } catch (const Error& e) {
                errors.note(e.what());
                continue;
            }
            for (const KeySpec& spec : schema)
                if (!spec.sweepable && sweep.overrides.count(spec.name))
                    throw Error(where(path, sweep.overrides[spec.name]->source()) + ": key '" + spec.name +
                                "' places the results: set it once, outside [[sweep]] tables");
        }
    }
    return sweep;
}

ConfigTables readTables(const std::string& path, const toml::table& root, const std::vector<KeySpec>& schema, ErrorList& errors) {
    const Sections sections(schema);
    ConfigTables tables;
    for (auto&& [sectionKey, sectionNode] : root) {
        if (sectionKey.str() != "sweep") {
            try {
                readSection(path, sections, sectionKey, sectionNode, tables.base, errors);
            } catch (const Error& e) {
                errors.note(e.what());
            }
            continue;
        }
        const toml::array* list = sectionNode.as_array();
        if (!list || !list->is_array_of_tables())
            throw Error(where(path, sectionKey.source()) + ": 'sweep' must be an array of tables ([[sweep]])");
        for (const toml::node& element : *list) tables.sweeps.push_back(readSweep(path, sections, schema, element, errors));
    }
    if (tables.sweeps.empty()) tables.sweeps.push_back(Sweep{});
    return tables;
}

// Alternative keys by group (KeySpec::group), in schema order.
using Groups = std::map<std::string, std::vector<std::string>>;

Groups keyGroups(const std::vector<KeySpec>& schema) {
    Groups groups;
    for (const KeySpec& spec : schema)
        if (!spec.group.empty()) groups[spec.group].push_back(spec.name);
    return groups;
}

// --set: each replaces its key (and the other keys of its group) in the base and every sweep. The
// values' nodes live in `settingTables`.
void applySettings(const std::vector<std::string>& settings, const std::vector<KeySpec>& schema, Groups& groups,
                   ConfigTables& tables, std::vector<toml::table>& settingTables) {
    settingTables.reserve(settings.size());  // the nodes stay where Given points
    for (const std::string& setting : settings) {
        const auto [key, node] = parseSetting(setting, settingTables, schema);
        const std::string& group = keySpec(key).group;
        for (const std::string& k : group.empty() ? std::vector<std::string>{key} : groups[group]) {
            tables.base.erase(k);
            for (Sweep& sweep : tables.sweeps) sweep.overrides.erase(k);
        }
        tables.base[key] = node;
    }
}

// The keys a sweep's runs see: the base's, then the sweep's. A sweep that gives one key of a group
// replaces the base's choice in that group.
Given sweepKeys(const Given& base, const Sweep& sweep, const Groups& groups) {
    Given given = base;
    for (const auto& [group, keys] : groups)
        if (std::any_of(keys.begin(), keys.end(), [&](const std::string& k) { return sweep.overrides.count(k); }))
            for (const std::string& k : keys) given.erase(k);
    for (const auto& [key, node] : sweep.overrides) given[key] = node;
    return given;
}

// The groups with a key given (at most one each: two is an error).
std::set<std::string> groupsGiven(const std::string& path, const Given& given, const Groups& groups, ErrorList& errors) {
    std::set<std::string> named;
    for (const auto& [group, keys] : groups) {
        std::vector<std::string> inGroup;
        for (const std::string& k : keys)
            if (given.count(k)) inGroup.push_back(k);
        if (inGroup.size() > 1)
            errors.note(where(path, given.at(inGroup[1])->source()) + ": keys " + join(inGroup, " and ") + " both set the " + group +
                        "; give exactly one");
        if (!inGroup.empty()) named.insert(group);
    }
    return named;
}

// A key's values: a list sweeps (an axis), else one value.
std::vector<ConfigValue> listValues(const std::string& path, const KeySpec& spec, const toml::node& node) {
    std::vector<ConfigValue> values;
    if (!isSweep(spec, node)) {
        values.push_back(convert(path, spec, node));
        return values;
    }
    const toml::array& list = *node.as_array();
    const std::string at = where(path, node.source()) + ": key '" + spec.name + "': ";
    if (list.empty()) throw Error(at + "an empty list sweeps nothing");
    if (!spec.sweepable) throw Error(at + "places the results and cannot be swept: give one value");
    // A scene description reads scale = [sx, sy, sz] as one per-axis scale; here a list sweeps the
    // uniform scale. Three numbers could mean either: say which.
    if (spec.name == "scene.scale" && list.size() == 3)
        if (std::all_of(list.begin(), list.end(), [](const toml::node& n) { return n.is_number(); }))
            throw Error(at + "a list of 3 numbers is ambiguous: in a config a list sweeps the uniform "
                        "scale (3 runs), but a scene description reads [sx, sy, sz] as one per-axis scale. "
                        "A per-axis scale belongs in a scene description ([[object]] scale); to sweep "
                        "3 uniform scales give each its own [[sweep]]");
    for (const toml::node& element : list) values.push_back(convert(path, spec, element));
    return values;
}

using Axes = std::vector<std::pair<std::string, std::vector<ConfigValue>>>;

// Each key of the schema: a single value, a default, or a list of values (an axis of the sweep).
Axes sweepAxes(const std::string& path, const std::vector<KeySpec>& schema, const Given& given,
               const std::set<std::string>& groupsNamed, ErrorList& errors) {
    Axes axes;
    for (const KeySpec& spec : schema) try {
        const auto it = given.find(spec.name);
        std::vector<ConfigValue> values;
        if (it != given.end()) {
            values = listValues(path, spec, *it->second);
        } else {
            if (spec.required) throw Error(path + ": missing required key '" + spec.name + "' (" + spec.help + ")");
            if (spec.defaultValue) values.push_back(*spec.defaultValue);
            if (spec.groupDefault && !groupsNamed.count(spec.group)) values.push_back(*spec.groupDefault);
        }
        if (!values.empty()) axes.emplace_back(spec.name, std::move(values));
    } catch (const Error& e) {
        errors.note(e.what());
    }
    return axes;
}

// Which given keys some run reads: a key no run reads is an error (it applies only elsewhere).
struct KeysRead {
    std::map<std::string, const toml::node*> unread;  // given keys no run has read yet
    std::set<std::string> read;                        // keys some run of some sweep reads
};

// Run r of the axes' Cartesian product (the last axis varying fastest), without the keys it does
// not read (KeySpec::appliesWhen).
RunConfig productRun(const Axes& axes, std::size_t r, const std::vector<KeySpec>& schema) {
    RunConfig run;
    for (auto it = axes.rbegin(); it != axes.rend(); ++it) {
        run.values[it->first] = it->second[r % it->second.size()];
        r /= it->second.size();
    }
    for (const KeySpec& spec : schema) {
        const bool applies = conditionsHold(spec.appliesWhen, [&](const std::string& key) {
            return run.has(key) ? std::optional<std::string>(formatValue(run.values.at(key))) : std::nullopt;
        });
        if (!applies) run.values.erase(spec.name);
    }
    return run;
}

// The sweep's runs into the plan: the product of its axes, less the runs a skip rule matches and
// runs another sweep already has (`seen`). A sweep that runs nothing, or a rule that matches no
// run, is an error.
void expandSweep(const std::string& path, const Sweep& sweep, const Axes& axes, const std::vector<KeySpec>& schema,
                 ExperimentPlan& plan, KeysRead& keys, std::set<std::string>& seen) {
    std::vector<std::string> swept;
    std::size_t total = 1;
    for (const auto& [key, values] : axes) {
        if (values.size() > 1) swept.push_back(key);
        total *= values.size();
        if (total > 100000) throw Error(path + ": the sweep expands to over 100000 runs");
    }
    std::size_t skippedRuns = 0;
    std::vector<std::size_t> skipMatches(sweep.skip.size(), 0);
    for (std::size_t r = 0; r < total; ++r) {
        RunConfig run = productRun(axes, r, schema);
        run.sweep = sweep.name;
        bool skipped = false;
        for (std::size_t k = 0; k < sweep.skip.size(); ++k)
            if (sweep.skip[k].matches(run)) {
                ++skipMatches[k];
                skipped = true;
            }
        if (skipped) {
            ++skippedRuns;
            continue;
        }
        for (const auto& [key, value] : run.values) {
            keys.unread.erase(key);
            keys.read.insert(key);
        }
        for (const std::string& key : swept)
            if (run.has(key)) run.sweptKeys.push_back(key);
        if (!seen.insert(sweep.name + "|" + run.canonical()).second) continue;
        run.index = plan.runs.size();
        plan.runs.push_back(std::move(run));
    }
    if (skippedRuns == total)
        throw Error(sweep.at + ": every one of the " + std::to_string(total) + " runs of sweep '" + sweep.name +
                    "' matches a skip rule: the sweep runs nothing");
    for (std::size_t k = 0; k < sweep.skip.size(); ++k)
        if (!skipMatches[k])
            throw Error(sweep.skip[k].at + ": key 'sweep.skip': the rule \"" + sweep.skip[k].text +
                        "\" matches no run of this sweep (a typo, or a value the sweep never takes?)");
}

}  // namespace

ExperimentPlan loadExperimentText(const std::string& configText, const std::string& path, const std::string& configDir,
                                  const std::vector<std::string>& settings) {
    ExperimentPlan plan;
    plan.configPath = path;
    plan.configText = configText;
    plan.configDir = configDir;
    plan.settings = settings;
    const toml::table root = parseToml(plan.configText, path);
    const std::vector<KeySpec>& schema = configSchema();
    ErrorList errors;
    ConfigTables tables = readTables(path, root, schema, errors);
    Groups groups = keyGroups(schema);
    std::vector<toml::table> settingTables;
    applySettings(settings, schema, groups, tables, settingTables);
    KeysRead keys;
    std::set<std::string> seen;  // canonical runs, to drop duplicates
    for (const Sweep& sweep : tables.sweeps) {
        const Given given = sweepKeys(tables.base, sweep, groups);
        for (const auto& [key, node] : given)
            if (!keys.read.count(key)) keys.unread.emplace(key, node);
        const std::set<std::string> groupsNamed = groupsGiven(path, given, groups, errors);
        const Axes axes = sweepAxes(path, schema, given, groupsNamed, errors);
        if (!errors.errors.empty()) continue;  // no runs from keys that are wrong (the errors are reported below)
        expandSweep(path, sweep, axes, schema, plan, keys, seen);
    }
    errors.throwIfAny(path);
    if (!keys.unread.empty()) {
        const auto& [key, node] = *keys.unread.begin();
        throw Error(where(path, node->source()) + ": key '" + key + "' is never read: it applies only when " +
                    join(keySpec(key).appliesWhen, " and "));
    }
    return plan;
}

void overrideKey(ExperimentPlan& plan, const std::string& key, const ConfigValue& value, const std::string& option) {
    const std::vector<KeySpec>& schema = configSchema();
    const auto spec = std::find_if(schema.begin(), schema.end(), [&](const KeySpec& k) { return k.name == key; });
    if (spec == schema.end()) throw Error(option + ": no config key " + key);
    // Checked as the key in a config file would be.
    toml::table t;
    std::visit([&](const auto& v) {
        if constexpr (std::is_same_v<std::decay_t<decltype(v)>, std::array<double, 3>>)
            t.insert("v", toml::array{v[0], v[1], v[2]});
        else
            t.insert("v", v);
    }, value);
    const ConfigValue checked = convert(option, *spec, *t.get("v"), option);
    for (RunConfig& run : plan.runs) run.values[key] = checked;
    plan.overrides[key] = formatValue(checked);
}

void overrideEmbreeConfig(ExperimentPlan& plan, const std::string& embreeConfig) {
    try {
        checkEmbreeConfig(embreeConfig);
    } catch (const Error& e) {
        throw Error("--embree-config: " + std::string(e.what()));
    }
    overrideKey(plan, "baseline.embree_config", embreeConfig, "--embree-config");
}

void applyRecordedOverrides(ExperimentPlan& plan, const std::map<std::string, std::string>& overrides) {
    const std::vector<KeySpec>& schema = configSchema();
    for (const auto& [key, text] : overrides) {
        const auto spec = std::find_if(schema.begin(), schema.end(), [&](const KeySpec& k) { return k.name == key; });
        if (spec == schema.end()) throw Error("context.json: override of unknown key " + key);
        ConfigValue value = text;
        if (spec->type == ValueType::Bool) value = text == "true";
        else if (spec->type != ValueType::String) throw Error("context.json: override of " + key + " is not supported");
        overrideKey(plan, key, value, "recorded override " + key);
    }
}

}  // namespace rtbench
