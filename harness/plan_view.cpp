#include "plan_view.h"

#include <algorithm>
#include <filesystem>
#include <iomanip>
#include <map>
#include <set>
#include <sstream>

#include "columns.h"
#include "output_folder.h"
#include "samples_check.h"
#include "core/error.h"
#include "rays/registry.h"

namespace rtbench {
namespace fs = std::filesystem;

std::vector<const RunConfig*> filterRuns(const ExperimentPlan& plan, const std::vector<std::string>& filters) {
    // "section.key=value" is a typed condition, as a skip rule's (structure.type=BVH is refused,
    // camera.fov_deg=30 matches 30.0); anything else is text of the label.
    std::vector<KeyConditions> conditions;
    for (const std::string& f : filters) {
        if (f.find_first_not_of(" \t") == std::string::npos) throw Error("--filter '" + f + "': an empty filter selects nothing");
        const std::size_t eq = f.find('=');
        const bool keyed = eq != std::string::npos && f.substr(0, eq).find('.') != std::string::npos;
        conditions.push_back(keyed ? parseKeyConditions("--filter " + f, f) : KeyConditions{});
    }
    std::vector<const RunConfig*> kept;
    for (const RunConfig& run : plan.runs) {
        bool all = true;
        for (std::size_t i = 0; i < filters.size() && all; ++i)
            all = conditions[i].empty() ? run.label().find(filters[i]) != std::string::npos : runMatches(run, conditions[i]);
        if (all) kept.push_back(&run);
    }
    return kept;
}

namespace {

// The rays a run traces, as far as the plan knows them (its ray type's PlannedRays): the camera
// rays of primary rays; for the later generations (their batch is the rays that continue from the
// hits) a bound, "<= N".
std::string tracedRays(const RunConfig& run, std::uint64_t cameraRays) {
    const RayType& type = rayType(run.getString("rays.type"));
    switch (type.planned) {
        case PlannedRays::OnePerCameraRay: return " " + std::to_string(cameraRays);
        case PlannedRays::About: return "~" + std::to_string(cameraRays);
        case PlannedRays::AtMost: break;
    }
    const auto perCameraRay = type.perCameraRayKey.empty() ? 1 : std::uint64_t(run.getInt(type.perCameraRayKey));
    return "<= " + std::to_string(cameraRays * perCameraRay);
}

}  // namespace

std::map<std::string, double> earlierWallSeconds(const std::vector<Row>& rows) {
    std::map<std::string, double> seconds;
    for (const Row& row : rows) {
        const auto it = row.find("wall_s");
        if (it == row.end() || it->second.empty() || !row.count("run") || !row.count("config_hash")) continue;
        char* end = nullptr;
        const double s = std::strtod(it->second.c_str(), &end);
        if (*end == '\0' && s >= 0.0) seconds[runKey(row)] = s;
    }
    return seconds;
}

std::string describePlan(const ExperimentPlan& plan, const RunnerOptions& options, const std::vector<std::string>& filters) {
    if (plan.runs.empty()) throw Error(plan.configPath + ": the plan has no runs");
    const RunConfig& first = plan.runs.front();
    const std::string output = options.outputOverride.empty() ? first.getString("experiment.output") : options.outputOverride;
    const std::string folder = experimentFolder(output, first.getString("experiment.name"));
    const std::vector<const RunConfig*> runs = filterRuns(plan, filters);
    // Earlier rows of the same runs: what they took.
    std::map<std::string, double> earlier;  // run|config_hash -> wall_s
    const std::string csv = (fs::path(folder) / "runs.csv").string();
    std::error_code ec;
    if (fs::is_regular_file(fs::symlink_status(csv, ec))) {
        try {
            earlier = earlierWallSeconds(readRunsCsv(csv));
        } catch (const Error&) {
            // an unreadable runs.csv gives no estimate; `rtbench run` says why it cannot resume
        }
    }
    std::set<std::string> swept;
    for (const RunConfig& run : plan.runs) swept.insert(run.sweptKeys.begin(), run.sweptKeys.end());
    std::ostringstream out;
    out << plan.configPath << ": " << plan.runs.size() << " run" << (plan.runs.size() == 1 ? "" : "s");
    if (!filters.empty()) out << ", " << runs.size() << " selected by --filter";
    out << " -> " << folder << "/\n";
    if (!swept.empty()) {
        out << "swept keys:";
        for (const std::string& k : swept) out << " " << k;
        out << "\n";
    }
    out << std::left << std::setw(5) << "run" << std::right << std::setw(12) << "rays" << std::setw(16) << "earlier wall s"
        << "  " << std::left << "parameters\n";
    double known = 0.0;
    std::size_t knownRuns = 0;
    std::uint64_t rays = 0;
    bool bounded = false;  // a run of rays after the first hit: its batch is known only as a bound
    for (const RunConfig* run : runs) {
        const std::uint64_t r = std::uint64_t(run->getInt("camera.width")) * std::uint64_t(run->getInt("camera.height"));
        rays += r;
        const std::string traced = tracedRays(*run, r);
        bounded = bounded || traced[0] != ' ';
        const auto it = earlier.find(runNumber(*run) + "|" + run->hash());
        std::string took = "-";
        if (it != earlier.end()) {
            known += it->second;
            ++knownRuns;
            took = formatNumber(it->second, 4);
        }
        out << std::left << std::setw(5) << runNumber(*run) << std::right << std::setw(12) << traced << std::setw(16) << took << "  "
            << std::left << run->label() << "\n";
    }
    if (bounded)
        out << "(<= N: rays after the first hit, at most N, as the batch holds only the rays that continue; ~N: "
               "Whitted rays, N camera rays, then as many as the hits' materials and lights make)\n";
    out << runs.size() << " run(s), " << rays << " camera rays in all; ";
    if (knownRuns == 0)
        out << "no earlier row of these runs in " << csv << " to estimate their time from\n";
    else
        out << knownRuns << " took " << formatNumber(known, 4) << " s before (a resume keeps the ok ones of the same commit)"
            << (knownRuns == runs.size() ? std::string("\n")
                                         : "; at their mean the other " + std::to_string(runs.size() - knownRuns) + " would take ~" +
                                               formatNumber(known / double(knownRuns) * double(runs.size() - knownRuns), 3) + " s\n");
    return out.str();
}

}  // namespace rtbench
