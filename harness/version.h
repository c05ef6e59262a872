// Build provenance recorded with every result.
#pragma once
#include <string>

namespace rtbench {
std::string gitCommit();    // short hash of the source tree at configure time
std::string cpuModel();     // /proc/cpuinfo "model name"
std::string utcNow();       // ISO 8601
std::string hostName();
std::string versionText();  // "rtbench 0.1 (commit abc1234, build Release)"
}  // namespace rtbench
