// A config run whole through the runner on the test device, as `rtbench run` runs it: the
// [experiment] and [device] sections the tests' configs share (results under `dir`, one timed
// repetition and no warm-up, the validation layer on), then the test's own `body`.
#pragma once
#include <string>

#include "harness/runner.h"
#include "tests/device/test_device.h"
#include "tests/temp_dir.h"

namespace rtbench {

inline RunnerOptions quietRunnerOptions() {
    RunnerOptions options;
    options.quiet = true;
    return options;
}


inline ExperimentResult runTestConfig(TempDir& dir, const std::string& name, const std::string& body,
                                      const RunnerOptions& options = quietRunnerOptions()) {
    const std::string path = dir.write(name + ".toml", "[experiment]\nname = \"" + name + "\"\noutput = \"" +
                                                           dir.file("out") + "\"\nrepetitions = 1\nwarmups = 0\n[device]\nname = \"" +
                                                           testDeviceName() + "\"\nvalidation = true\n" + body);
    return runExperiment(loadExperiment(path), options);
}

}  // namespace rtbench
