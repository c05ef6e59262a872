#include "output_folder.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "structures/error.h"

namespace rtbench {
namespace fs = std::filesystem;

std::string experimentFolder(const std::string& output, const std::string& name) {
    const bool control = std::any_of(name.begin(), name.end(),
                                     [](char c) { return static_cast<unsigned char>(c) < 0x20; });
    if (name.empty() || name == "." || name == ".." || name.find('/') != std::string::npos ||
        name.find('\\') != std::string::npos || control)
        throw Error("experiment.name '" + name +
                    "' is not a plain folder name (no '/', not '.' or '..'): results go to "
                    "<output>/<name>/");
    return (fs::path(output) / name).string();
}

OutputFolderLock::OutputFolderLock(const std::string& folder) {
    const std::string path = (fs::path(folder) / ".rtbench.lock").string();
    fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) throw Error(path + ": cannot create the lock file: " + std::strerror(errno));
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
        const int why = errno;
        char holder[32] = {0};
        const ssize_t n = ::pread(fd_, holder, sizeof holder - 1, 0);
        ::close(fd_);
        fd_ = -1;
        if (why == EWOULDBLOCK)
            throw Error(folder + ": another rtbench process (pid " +
                        (n > 0 ? std::string(holder, std::size_t(n)) : "?") +
                        ") is writing this results folder; wait for it or use another -o / "
                        "experiment.name");
        throw Error(path + ": cannot lock: " + std::strerror(why));
    }
    const std::string pid = std::to_string(::getpid());
    if (::ftruncate(fd_, 0) != 0 || ::pwrite(fd_, pid.data(), pid.size(), 0) != ssize_t(pid.size()))
        throw Error(path + ": cannot write the lock holder's pid: " + std::strerror(errno));
}

OutputFolderLock::~OutputFolderLock() {
    if (fd_ >= 0) ::close(fd_);  // releases the flock; the file stays (removing it would race)
}

void checkWritableFile(const std::string& path) {
    std::error_code ec;
    const fs::file_status status = fs::symlink_status(path, ec);
    if (!fs::exists(status)) return;
    if (!fs::is_regular_file(status))
        throw Error(path + ": exists but is not a regular file; move it away first");
    if (::access(path.c_str(), W_OK) != 0 && errno != ENOENT)
        throw Error(path + ": not writable: " + std::strerror(errno));
}

}  // namespace rtbench
