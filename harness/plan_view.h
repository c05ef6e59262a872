// `rtbench plan CONFIG` (and `rtbench run --dry-run`): the runs a config makes, with their swept
// parameters and what they will cost, without running anything.
#pragma once
#include <map>
#include <string>
#include <vector>

#include "config.h"
#include "runner.h"

namespace rtbench {

// Keeps the runs that match every filter: "section.key=value" (the value typed as the key's own, as
// a sweep.skip rule reads it: camera.fov_deg=30 matches 30.0) or else a text found in the run's
// label (min_dim=16). Throws rtbench::Error naming a section.key=value filter whose key is no
// config key or whose value the key refuses (structure.type=BVH), and an empty filter.
std::vector<const RunConfig*> filterRuns(const ExperimentPlan& plan, const std::vector<std::string>& filters);

// What earlier rows of runs took: "run|config_hash" -> wall_s, for the rows whose wall_s is a
// number (the plan's estimate, and the time left on `run`'s progress line).
std::map<std::string, double> earlierWallSeconds(const std::vector<Row>& rows);

// The table: run, rays, the time an earlier row of the same run took (runs.csv in the output
// folder, same config_hash), its label; then an estimate of the whole from those rows.
std::string describePlan(const ExperimentPlan& plan, const RunnerOptions& options, const std::vector<std::string>& filters);

}  // namespace rtbench
