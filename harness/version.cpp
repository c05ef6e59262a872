#include "version.h"

#include "git_commit.h"  // generated at build time: RTBENCH_GIT_COMMIT

#include <unistd.h>

#include <ctime>
#include <fstream>

namespace rtbench {

std::string gitCommit() { return RTBENCH_GIT_COMMIT; }

std::string cpuModel() {
    std::ifstream in("/proc/cpuinfo");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
    return "unknown";
}

std::string utcNow() {
    std::time_t now = std::time(nullptr);
    char buf[32];
    std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
    return buf;
}

std::string versionText() {
    return std::string("rtbench ") + RTBENCH_VERSION + " (commit " + RTBENCH_GIT_COMMIT + ", build " + RTBENCH_BUILD_NAME + ")";
}

std::string hostName() {
    char buf[256] = {};
    gethostname(buf, sizeof buf - 1);
    return buf;
}

}  // namespace rtbench
