// Experiment configs (TOML, toml++): a schema of every key with its type, default, range and
// help; validation whose errors name the file, line and key and list what is allowed; and the
// plan: one run per combination of list-valued keys (cartesian product, in schema order).
#pragma once
#include <map>
#include <string>
#include <vector>

#include "schema/keys.h"

namespace rtbench {

// Every key rtbench reads: the common keys, then each structure's and strategy's (with
// appliesWhen naming its structure.type or strategy.type). Unknown keys are errors.
const std::vector<KeySpec>& configSchema();
// The spec of one key of configSchema(); throws naming the key when there is none.
const KeySpec& keySpec(const std::string& name);
// What a key takes, for `rtbench keys`: "an integer in [1, 1000]", "a string: one of a, b", ...
std::string keyTypeText(const KeySpec& key);

struct ExperimentPlan {
    std::string configPath;
    std::string configText;
    std::string configDir;  // relative scene paths resolve against it
    std::vector<RunConfig> runs;
    // Keys the command line set in every run (-d, --validation, --embree-config), as formatValue
    // writes them: recorded in context.json, so `rtbench check` re-runs what ran.
    std::map<std::string, std::string> overrides;
    // The command line's --set "section.key=value" (value as TOML: a list sweeps), applied over the
    // file's sections and sweeps: recorded in context.json beside the config text.
    std::vector<std::string> settings;
};

// Parses and validates a config file; throws rtbench::Error with file:line: key: message.
// The sections give base values; each [[sweep]] table (optional `name`, then sections of its own)
// overrides them, and the plan is the union of the sweeps' cartesian products, without duplicates.
// `settings` ("section.key=value", the command line's --set) replace the key wherever the file
// sets it, base or [[sweep]], and are checked as the file's keys are (errors name the --set).
ExperimentPlan loadExperiment(const std::string& path, const std::vector<std::string>& settings = {});
// The same for config text that names `path` in its errors and resolves scenes against configDir.
ExperimentPlan loadExperimentText(const std::string& configText, const std::string& path, const std::string& configDir,
                                  const std::vector<std::string>& settings = {});

// Sets baseline.embree_config of every run (the command line's --embree-config, e.g. "isa=avx2"
// where Embree's default ISA choice crashes); throws naming the option if the string is invalid.
void overrideEmbreeConfig(ExperimentPlan& plan, const std::string& embreeConfig);

// "section.key=value ..." as a sweep.skip rule reads it: each value typed as its key's own (30 =
// 30.0, [1, 0, 0]) and checked as the key would be; throws rtbench::Error naming `at` on an
// unknown key, a value the key refuses, or no condition at all.
using KeyConditions = std::vector<std::pair<std::string, ConfigValue>>;
KeyConditions parseKeyConditions(const std::string& at, const std::string& text);
// True when the run has every key of `conditions` at its value (a key the run does not read: false).
bool runMatches(const RunConfig& run, const KeyConditions& conditions);

// Sets `key` to `value` in every run (the command line's -d sets device.name, --validation
// device.validation): the run's parameters, hash and identity record what ran. `option` names
// the command-line option in errors; the value is checked as the config key would be.
void overrideKey(ExperimentPlan& plan, const std::string& key, const ConfigValue& value, const std::string& option);

// Applies context.json's recorded "overrides" (key -> value as formatValue writes it).
void applyRecordedOverrides(ExperimentPlan& plan, const std::map<std::string, std::string>& overrides);

}  // namespace rtbench
