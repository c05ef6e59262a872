// Whole runs of a ray type: a config of `body` after an [experiment] of one quick repetition on
// the test device, written into a temporary folder and run (tests of tests/rays/).
#pragma once
#include <gtest/gtest.h>

#include <string>

#include "harness/runner.h"
#include "tests/device/test_device.h"
#include "tests/temp_dir.h"

namespace rtbench {

class WorkloadRuns : public ::testing::Test {
protected:
    ExperimentResult run(const std::string& body) {
        const std::string path = dir_.write("runs.toml", "[experiment]\nname = \"runs\"\noutput = \"" + dir_.file("out") +
                                                             "\"\nrepetitions = 1\nwarmups = 0\nrounds = 1\n[device]\nname = \"" +
                                                             testDeviceName() + "\"\nvalidation = true\n" + body);
        RunnerOptions options;
        options.quiet = true;
        return runExperiment(loadExperiment(path), options);
    }
    TempDir dir_;
};

}  // namespace rtbench
