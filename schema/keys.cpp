#include "keys.h"

#include "columns.h"

#include <cstdio>
#include <sstream>

namespace rtbench {

std::string formatValue(const ConfigValue& value) {
    struct Visitor {
        std::string operator()(std::int64_t v) const { return std::to_string(v); }
        std::string operator()(double v) const {
            std::ostringstream s;
            s.precision(9);
            s << v;
            return s.str();
        }
        std::string operator()(const std::string& v) const { return v; }
        std::string operator()(bool v) const { return v ? "true" : "false"; }
        std::string operator()(const std::array<double, 3>& v) const {
            return "[" + (*this)(v[0]) + " " + (*this)(v[1]) + " " + (*this)(v[2]) + "]";
        }
    };
    return std::visit(Visitor{}, value);
}

namespace {
bool isVector(const KeySpec& key) { return key.type == ValueType::Int3 || key.type == ValueType::Float3; }
}  // namespace

std::vector<std::string> keyColumns(const KeySpec& key) {
    const std::string column = paramColumn(key.name);
    if (!isVector(key)) return {column};
    return {column + "_x", column + "_y", column + "_z"};
}

std::vector<std::pair<std::string, std::string>> keyCells(const KeySpec& key, const ConfigValue& value) {
    const std::vector<std::string> columns = keyColumns(key);
    if (!isVector(key)) return {{columns[0], formatValue(value)}};
    const auto& v = std::get<std::array<double, 3>>(value);
    std::vector<std::pair<std::string, std::string>> cells;
    for (int a = 0; a < 3; ++a) cells.emplace_back(columns[a], formatValue(v[a]));
    return cells;
}

bool conditionsHold(const std::vector<std::string>& conditions,
                    const std::function<std::optional<std::string>(const std::string& key)>& valueOf) {
    for (const std::string& condition : conditions) {
        const std::size_t eq = condition.find('=');
        const std::optional<std::string> value = valueOf(condition.substr(0, eq));
        if (!value) return false;
        // "key=a|b": either value.
        bool any = false;
        for (std::size_t from = eq + 1; !any;) {
            const std::size_t bar = condition.find('|', from);
            any = *value == condition.substr(from, bar == std::string::npos ? std::string::npos : bar - from);
            if (bar == std::string::npos) break;
            from = bar + 1;
        }
        if (!any) return false;
    }
    return true;
}

std::int64_t RunConfig::getInt(const std::string& key) const { return std::get<std::int64_t>(values.at(key)); }
double RunConfig::getFloat(const std::string& key) const { return std::get<double>(values.at(key)); }
const std::string& RunConfig::getString(const std::string& key) const { return std::get<std::string>(values.at(key)); }
bool RunConfig::getBool(const std::string& key) const { return std::get<bool>(values.at(key)); }
std::array<double, 3> RunConfig::getVec3(const std::string& key) const {
    return std::get<std::array<double, 3>>(values.at(key));
}

std::string RunConfig::canonical() const {
    std::string out;
    for (const auto& [key, value] : values) out += key + "=" + formatValue(value) + ";";
    return out;
}

std::string RunConfig::hash() const { return hex64(fnv1a64(canonical())); }

std::string RunConfig::hashWithout(const std::set<std::string>& keys) const {
    std::string out;
    for (const auto& [key, value] : values)
        if (!keys.count(key)) out += key + "=" + formatValue(value) + ";";
    return hex64(fnv1a64(out));
}

std::string RunConfig::label() const {
    std::string params;
    for (const std::string& key : sweptKeys) params += (params.empty() ? "" : " ") + key + "=" + formatValue(values.at(key));
    if (sweep.empty()) return params.empty() ? "single run" : params;
    return params.empty() ? sweep : sweep + ":" + params;
}

}  // namespace rtbench
