// Whole runs of a ray type: a config of `body` run through the runner on the test device
// (tests/harness/test_experiment.h runTestConfig), in a temporary folder (tests of tests/rays/).
#pragma once
#include <gtest/gtest.h>

#include <string>

#include "tests/harness/test_experiment.h"

namespace rtbench {

class WorkloadRuns : public ::testing::Test {
protected:
    ExperimentResult run(const std::string& body) { return runTestConfig(dir_, "runs", body); }
    TempDir dir_;
};

}  // namespace rtbench
