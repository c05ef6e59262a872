// rtbench merge: a sharded sweep's runs.shard-<i>-of-<n>.csv joined into runs.csv.
#pragma once
#include <string>
#include <vector>

#include "schema/columns.h"

namespace rtbench {

// Joins the shards' CSVs of a results folder into runs.csv; checks that every run of the plan
// (from the shards' context files) is there exactly once. With `missingReason`, a run no shard
// finished (a shard killed by a time limit, or never started) is a failed row instead, its error
// "no row from its shard: " + missingReason, its identity from the recorded plan and the other
// rows' device. Returns the merged rows.
std::vector<Row> mergeShards(const std::string& folder, const std::string& missingReason = "");

}  // namespace rtbench
