// Config keys as every part of rtbench declares and reads them: a key's spec (type, default,
// range, help, when it applies) and one run's values. The schema (harness/config.h) gathers the
// common keys and those each structure and strategy declares (methods/registry.h).
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "core/input_file.h"  // fnv1a64

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
    // "section.key=value" conditions under which the key is read (all must hold; "key=a|b": either
    // value); a run where
    // one fails drops the key, and a key given but read by no run is an error.
    std::vector<std::string> appliesWhen = {};
    // Strings: a further check that throws rtbench::Error saying what is wrong (the loader adds
    // the file, line and key).
    std::function<void(const std::string&)> check = {};
    // Alternatives: keys with the same group name set the same thing (e.g. the grid resolution
    // rule) and at most one of them may be given; a [[sweep]] that gives one replaces the base's.
    // When none is given, the key with a groupDefault takes it.
    std::string group = {};
    std::optional<ConfigValue> groupDefault = {};
    // False for keys that place the results (experiment.name, experiment.output): one value per
    // config, never a list, the same in every [[sweep]].
    bool sweepable = true;
    // The results schema (kSchemaVersion, schema/columns.h) that added the key's column (keys
    // of earlier schemas get theirs from harness/columns.cpp's history).
    int since = 1;
};

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
    // fnv1a64 of canonical(), hex.
    std::string hash() const;
    // The same with these keys left out too: the hash an older rtbench gave the run, whose schema
    // had no such keys (rtbench check on an older results folder).
    std::string hashWithout(const std::set<std::string>& keys) const;
    // A short label naming the swept parameters, e.g. "structure.min_dim=32".
    std::string label() const;
};

std::string formatValue(const ConfigValue& value);

// A key's runs.csv columns, each with its cell of `value`: "section_key", or for a 3-vector key
// (Int3, Float3) "section_key_x", "_y" and "_z", each a plain number (results schema 6; before it,
// one "[x y z]" cell that readers split, harness/columns.cpp).
std::vector<std::string> keyColumns(const KeySpec& key);
std::vector<std::pair<std::string, std::string>> keyCells(const KeySpec& key, const ConfigValue& value);

// Whether every "section.key=value" (or "section.key=a|b") condition (KeySpec::appliesWhen, ColumnSpec::appliesWhen)
// holds, `valueOf(key)` giving the key's value as formatValue writes it, or nothing when unset.
bool conditionsHold(const std::vector<std::string>& conditions,
                    const std::function<std::optional<std::string>(const std::string& key)>& valueOf);

}  // namespace rtbench
