// Experiment configs (TOML, toml++): a schema of every key with its type, default, range and
// help; validation whose errors name the file, line and key and list what is allowed; and the
// plan: one run per combination of list-valued keys (cartesian product, in schema order).
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace rtbench {

using ConfigValue = std::variant<std::int64_t, double, std::string, bool, std::array<double, 3>>;

enum class ValueType { Int, Float, String, Bool, Int3, Float3 };

struct KeySpec {
    std::string name;  // "section.key"
    ValueType type;
    std::string help;
    std::optional<ConfigValue> defaultValue;  // none: optional without default (or required)
    bool required = false;
    double min = -1e300, max = 1e300;   // numeric range (each component for Int3/Float3)
    std::vector<std::string> choices;   // allowed strings, when a closed set
    // "section.key=value" conditions under which the key is read (all must hold); a run where
    // one fails drops the key, and a key given but read by no run is an error.
    std::vector<std::string> appliesWhen = {};
    // Strings: a further check that throws rtbench::Error saying what is wrong (the loader adds
    // the file, line and key).
    std::function<void(const std::string&)> check = {};
};

// Every key rtbench reads. Unknown keys are errors.
const std::vector<KeySpec>& configSchema();

// One run: every schema key that has a value (given or default), scalar.
struct RunConfig {
    std::size_t index = 0;                      // 0-based position in the plan
    std::string sweep;                          // name of the [[sweep]] it comes from, or ""

    std::map<std::string, ConfigValue> values;  // "section.key" -> value
    std::vector<std::string> sweptKeys;         // keys that vary across the plan

    bool has(const std::string& key) const { return values.count(key) != 0; }
    std::int64_t getInt(const std::string& key) const;
    double getFloat(const std::string& key) const;
    const std::string& getString(const std::string& key) const;
    bool getBool(const std::string& key) const;
    std::array<double, 3> getVec3(const std::string& key) const;
    // "key=value" pairs joined; stable across runs of the same parameters.
    std::string canonical() const;
    // FNV-1a 64-bit of canonical(), hex.
    std::string hash() const;
    // A short label naming the swept parameters, e.g. "structure.min_dim=32".
    std::string label() const;
};

std::string formatValue(const ConfigValue& value);

struct ExperimentPlan {
    std::string configPath;
    std::string configText;
    std::string configDir;  // relative scene paths resolve against it
    std::vector<RunConfig> runs;
};

// Parses and validates a config file; throws rtbench::Error with file:line: key: message.
// The sections give base values; each [[sweep]] table (optional `name`, then sections of its own)
// overrides them, and the plan is the union of the sweeps' cartesian products, without duplicates.
ExperimentPlan loadExperiment(const std::string& path);
// The same for config text that names `path` in its errors and resolves scenes against configDir.
ExperimentPlan loadExperimentText(const std::string& configText, const std::string& path, const std::string& configDir);

}  // namespace rtbench
