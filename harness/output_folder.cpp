#include "output_folder.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <set>
#include <tuple>
#include <utility>

#include "core/error.h"
#include "core/text.h"
#include "version.h"
#include "writers.h"

namespace rtbench {
namespace fs = std::filesystem;

std::string experimentFolder(const std::string& output, const std::string& name) {
    const bool control = std::any_of(name.begin(), name.end(),
                                     [](char c) { return static_cast<unsigned char>(c) < 0x20; });
    if (name.empty() || name == "." || name == ".." || name.find('/') != std::string::npos ||
        name.find('\\') != std::string::npos || control)
        throw Error("experiment.name '" + printable(name) +
                    "' is not a plain folder name (no '/', not '.' or '..'): results go to "
                    "<output>/<name>/");
    return (fs::path(output) / name).string();
}

namespace {

// Opens (creating) a lock file without following a symlink.
int openLockFile(const std::string& path) {
    const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd < 0) {
        if (errno == ELOOP)
            throw Error(path + ": is a symlink; rtbench never writes through one: remove it");
        throw Error(path + ": cannot create the lock file: " + std::strerror(errno));
    }
    return fd;
}

// The holder's pid as it wrote it. It writes it just after locking: a moment's wait covers a
// holder that has locked but not yet written.
std::string pidIn(int fd) {
    for (int attempt = 0; attempt < 20; ++attempt) {
        char holder[32] = {0};
        const ssize_t n = ::pread(fd, holder, sizeof holder - 1, 0);
        if (n > 0) return std::string(holder, std::size_t(n));
        ::usleep(10000);
    }
    return "? (it wrote none)";
}

void writePid(int fd, const std::string& path) {
    const std::string pid = std::to_string(::getpid());
    if (::ftruncate(fd, 0) != 0 || ::pwrite(fd, pid.data(), pid.size(), 0) != ssize_t(pid.size()))
        throw Error(path + ": cannot write the lock holder's pid: " + std::strerror(errno));
}

// The pids of the processes whose lock on a lock file of `folder` (<prefix>*.lock) keeps
// `operation` from being taken now: LOCK_EX, any holder; LOCK_SH, an exclusive one. A holder that
// is ending holds its lock exclusively for a moment: a refusal is asked twice.
std::string lockHolders(const std::string& folder, const std::string& prefix, int operation) {
    std::string pids;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(folder, ec)) {
        const std::string name = entry.path().filename().string();
        const bool lockFile = name.rfind(prefix, 0) == 0 && name.size() > 5 && name.substr(name.size() - 5) == ".lock";
        if (!lockFile || entry.is_symlink(ec)) continue;
        const int fd = ::open(entry.path().c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
        if (fd < 0) continue;
        bool held = ::flock(fd, operation | LOCK_NB) != 0;
        if (held) {
            ::usleep(50000);
            held = ::flock(fd, operation | LOCK_NB) != 0;
        }
        if (held) pids += (pids.empty() ? "" : ", ") + pidIn(fd);
        ::close(fd);
    }
    return pids;
}

// The pids of the shard runs holding their locks in `folder` now.
std::string runningShards(const std::string& folder) { return lockHolders(folder, ".rtbench.shard-", LOCK_EX); }

}  // namespace

namespace {

// Opens `path` and flocks it (LOCK_EX or LOCK_SH) without waiting: the descriptor, or -1 when
// another process holds it (its pid, as written in the file, in `holder`).
// A holder removes its lock file when it ends (~OutputFolderLock); a lock taken on a file that
// was removed meanwhile guards nothing, so it is taken again on the file the path names now.
int tryLock(const std::string& path, int operation, std::string& holder) {
    auto stillNamed = [&](int fd) {
        struct stat opened{}, named{};
        return ::fstat(fd, &opened) == 0 && ::lstat(path.c_str(), &named) == 0 && opened.st_dev == named.st_dev &&
               opened.st_ino == named.st_ino;
    };
    for (int attempt = 0; attempt < 100; ++attempt) {
        const int fd = openLockFile(path);
        const bool locked = ::flock(fd, operation | LOCK_NB) == 0;
        const int why = errno;
        if (!stillNamed(fd)) {  // removed or replaced after we opened it (its last holder ending)
            ::close(fd);
            continue;
        }
        if (locked) return fd;
        // A holder that is ending takes its lock exclusively for a moment before removing the
        // file: one that is gone a moment later was no writer.
        ::usleep(20000);
        if (why == EWOULDBLOCK && !stillNamed(fd)) {
            ::close(fd);
            continue;
        }
        holder = pidIn(fd);
        ::close(fd);
        if (why != EWOULDBLOCK) throw Error(path + ": cannot lock: " + std::strerror(why));
        return -1;
    }
    throw Error(path + ": cannot lock: the lock file keeps being removed and made again");
}

}  // namespace

OutputFolderLock::OutputFolderLock(const std::string& folder) {
    const std::string path = (fs::path(folder) / ".rtbench.lock").string();
    std::string holder;
    const int fd = tryLock(path, LOCK_EX, holder);
    if (fd < 0) {
        const std::string shards = runningShards(folder);
        if (!shards.empty())
            throw Error(folder + ": shard runs (pid " + shards +
                        ") are writing this results folder; wait for them (then `rtbench merge`) or use "
                        "another -o / experiment.name");
        throw Error(folder + ": another rtbench process (pid " + holder +
                    ") is writing this results folder; wait for it or use another -o / experiment.name");
    }
    held_.push_back({fd, path, true});
    try {
        writePid(fd, path);
    } catch (...) {
        ::close(fd);
        throw;
    }
}

OutputFolderLock::OutputFolderLock(const std::string& folder, const std::string& shard) {
    std::string holder;
    const int fd = tryLock((fs::path(folder) / ".rtbench.lock").string(), LOCK_SH, holder);
    if (fd < 0)
        throw Error(folder + ": another rtbench process (pid " + holder +
                    ") is writing this whole results folder (a run without --shard, or a merge); wait for it");
    const std::string folderPath = (fs::path(folder) / ".rtbench.lock").string();
    const std::string shardPath = (fs::path(folder) / (".rtbench." + shard + ".lock")).string();
    int shardFd = -1;
    try {
        shardFd = tryLock(shardPath, LOCK_EX, holder);
    } catch (...) {
        ::close(fd);
        throw;
    }
    if (shardFd < 0) {
        ::close(fd);  // a constructor that throws runs no destructor
        throw Error(folder + ": another rtbench process (pid " + holder + ") is writing " + shard +
                    " of this results folder; wait for it");
    }
    held_ = {{fd, folderPath, false}, {shardFd, shardPath, true}};
    try {
        writePid(shardFd, shardPath);
    } catch (...) {
        ::close(fd);
        ::close(shardFd);
        throw;
    }
}

OutputFolderLock::~OutputFolderLock() {
    // Each lock file is removed by its last holder, while it still holds it exclusively (a process
    // that opened it meanwhile finds its lock on a removed file and locks again: tryLock); a
    // shared lock that other shards hold stays. Closing releases the flocks.
    for (auto it = held_.rbegin(); it != held_.rend(); ++it) {
        if (it->exclusive || ::flock(it->fd, LOCK_EX | LOCK_NB) == 0) ::unlink(it->path.c_str());
        ::close(it->fd);
    }
}

namespace {

// (device, inode) of `folder` itself (lstat: a link is not followed); throws unless a real folder.
std::pair<unsigned long long, unsigned long long> folderNode(const std::string& folder, const char* when) {
    struct stat st {};
    if (::lstat(folder.c_str(), &st) != 0)
        throw Error(folder + ": the results folder " + when + " is gone (" + std::strerror(errno) +
                    "); rtbench writes only into the folder it opened");
    if (S_ISLNK(st.st_mode) || !S_ISDIR(st.st_mode))
        throw Error(folder + ": the results folder " + when + " is " + (S_ISLNK(st.st_mode) ? "a symlink" : "not a folder") +
                    "; rtbench never writes through one");
    return {static_cast<unsigned long long>(st.st_dev), static_cast<unsigned long long>(st.st_ino)};
}

}  // namespace

FolderIdentity::FolderIdentity(std::string folder) : folder_(std::move(folder)) {
    std::tie(device_, inode_) = folderNode(folder_, "when opened");
    fd_ = ::open(folder_.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    struct stat st {};
    if (fd_ < 0 || ::fstat(fd_, &st) != 0 || std::make_pair(static_cast<unsigned long long>(st.st_dev),
                                                           static_cast<unsigned long long>(st.st_ino)) != std::make_pair(device_, inode_)) {
        if (fd_ >= 0) ::close(fd_);
        throw Error(folder_ + ": the results folder changed while it was opened; rtbench writes only into the folder it opened");
    }
    holdFolder(folder_, fd_);  // every write into it goes through fd_ from now on (writers.h)
}

FolderIdentity::~FolderIdentity() {
    releaseFolder(folder_, fd_);
    ::close(fd_);
}

void FolderIdentity::check() const {
    if (folderNode(folder_, "now") != std::make_pair(device_, inode_))
        throw Error(folder_ + ": the results folder was replaced while the sweep ran (another folder now has its "
                              "name); rtbench writes only into the folder it opened");
}

void refuseSymlinks(const std::string& folder) {
    std::error_code ec;
    if (fs::is_symlink(fs::symlink_status(folder, ec)))
        throw Error(folder + ": the results folder is a symlink; rtbench writes only into a real folder "
                             "(give -o the folder it points to)");
    for (const auto& entry : fs::directory_iterator(folder, ec))
        if (entry.is_symlink(ec))
            throw Error(entry.path().string() +
                        ": a symlink in the results folder; rtbench never writes through one and refuses a "
                        "folder holding one: remove it");
    if (ec) throw Error(folder + ": cannot list the results folder: " + ec.message());
}

void checkWritableFile(const std::string& path) {
    std::error_code ec;
    const fs::file_status status = fs::symlink_status(path, ec);
    if (!fs::exists(status)) return;
    if (fs::is_symlink(status)) throw Error(path + ": is a symlink; rtbench never writes through one: remove it");
    if (!fs::is_regular_file(status))
        throw Error(path + ": exists but is not a regular file; move it away first");
    if (::access(path.c_str(), W_OK) != 0 && errno != ENOENT)
        throw Error(path + ": not writable: " + std::strerror(errno));
}

void refuseFolderBeingWritten(const std::string& folder, const std::string& command) {
    if (const std::string pids = lockHolders(folder, ".rtbench.", LOCK_SH); !pids.empty())
        throw Error(folder + ": being written by rtbench (pid " + pids + "): " + command + " it when that run ends");
}

ScratchFolder::ScratchFolder(const std::string& stem) : path_((fs::temp_directory_path() / (stem + "-XXXXXX")).string()) {
    if (!::mkdtemp(path_.data())) throw Error(path_ + ": cannot create the scratch folder: " + std::strerror(errno));
}

ScratchFolder::~ScratchFolder() {
    std::error_code ec;
    fs::remove_all(path_, ec);
}

std::string supersededPrefix(const std::string& folder) {
    std::string stamp = utcNow();
    stamp.erase(std::remove(stamp.begin(), stamp.end(), ':'), stamp.end());
    stamp.erase(std::remove(stamp.begin(), stamp.end(), '-'), stamp.end());
    std::set<std::string> names;  // every name in the folder: a prefix no file has yet
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(folder, ec)) names.insert(entry.path().filename().string());
    for (int k = 0;; ++k) {
        const std::string name = "superseded-" + stamp + (k ? "-" + std::to_string(k) : "") + "-";
        const auto after = names.lower_bound(name);
        if (after == names.end() || after->rfind(name, 0) != 0) return (fs::path(folder) / name).string();
    }
}

}  // namespace rtbench
