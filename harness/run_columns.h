// The columns every run writes whatever its methods: who it is (run, label, hashes, where it ran)
// and how it ended (status, error, warnings, wall time). Declared once, here, for the stages that
// write them: identityRow (harness/runner.cpp), the sweep's record (harness/sweep.cpp), the
// scene's inputs (harness/run_inputs.cpp) and addWarning (schema/warnings.h).
#pragma once
#include <string>

#include "schema/column.h"

namespace rtbench {

struct RunColumns {
    using K = ColumnKind;
    using Text = Column<std::string>;
    ColumnGroup identity;
    Text run = identity.add<std::string>({"run", K::Parameter, "", "run number in the plan (000, 001, ...)"});
    Text label = identity.add<std::string>({"label", K::Parameter, "", "the swept parameters of the run"});
    Text sweep = identity.add<std::string>({"sweep", K::Parameter, "", "the name of the [[sweep]] the run comes from (empty: the base config)", 0.0, false, {}, 5});
    Text status = identity.add<std::string>({"status", K::Exact, "", "ok or failed"});
    Text error = identity.add<std::string>({"error", K::Exact, "", "why the run failed"});
    Text warnings = identity.add<std::string>({"warnings", K::Exact, "", "what the run did that may surprise (e.g. triangles degenerate in float)"});
    Text configHash = identity.add<std::string>(
        {"config_hash", K::Parameter, "", "FNV-1a 64 of the run's parameters (the command line's -d, --validation and --embree-config included)"});
    Text inputsHash = identity.add<std::string>(
        {"inputs_hash", K::Parameter, "",
         "FNV-1a 64 over the contents of every file the scene was made from (mesh files, the scene description and its meshes, a cgal: "
         "mesh's cached file; none for procedural scenes): with config_hash, git_commit, device, driver and cpu, the run's identity"});
    Text inputFiles = identity.add<std::string>(
        {"input_files", K::Context, "", "those files: path (bytes, FNV-1a 64 of the contents), in reading order"});
    Text gitCommit = identity.add<std::string>({"git_commit", K::Context, "", "commit of the binary"});
    Text device = identity.add<std::string>({"device", K::Context, "", "Vulkan device name"});
    Text driver = identity.add<std::string>({"driver", K::Context, "", "Vulkan driver name and version"});
    Text cpu = identity.add<std::string>({"cpu", K::Context, "", "the host's CPU model (what lavapipe and Embree ran on)"});
    // The run's wall time, last of runs.csv's columns.
    Column<double> wallSeconds{{"wall_s", K::Timing, "s", "wall time of the whole run"}, 4};
};

const RunColumns& runColumnsDeclared();

}  // namespace rtbench
