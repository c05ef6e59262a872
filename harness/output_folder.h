// The folder an experiment writes: <output>/<experiment.name>/, checked before any run starts,
// never written through a symlink, and locked against a second writer.
#pragma once
#include <string>
#include <vector>

namespace rtbench {

// <output>/<name>; throws rtbench::Error unless `name` is a plain folder name (no separator,
// not "." or "..", not absolute, no control characters), so results never land outside `output`.
std::string experimentFolder(const std::string& output, const std::string& name);

// Locks on a results folder (flock, released when the process ends however it ends, so a killed
// run never leaves the folder locked). A whole-plan run and `rtbench merge` hold the folder's
// lock (.rtbench.lock) exclusively; a shard run holds it shared, so shards run side by side, and
// holds its own shard's lock (.rtbench.<shard>.lock) exclusively. A process that cannot lock
// fails at once, naming the holder's pid. Lock files are opened without following symlinks, and
// removed by their last holder when it ends (a killed process leaves its file, unlocked).
class OutputFolderLock {
  public:
    // The whole folder.
    explicit OutputFolderLock(const std::string& folder);
    // One shard ("shard-0-of-2") of the folder.
    OutputFolderLock(const std::string& folder, const std::string& shard);
    ~OutputFolderLock();
    OutputFolderLock(const OutputFolderLock&) = delete;
    OutputFolderLock& operator=(const OutputFolderLock&) = delete;

  private:
    struct Held {
        int fd;
        std::string path;
        bool exclusive;
    };
    std::vector<Held> held_;
};

// The results folder a sweep writes into, as it was when opened (device and inode): before each
// write the runner checks that the path still names that real folder, so a folder renamed away
// mid-run and a symlink (or another folder) put in its place is refused, not written through.
//
// It also holds the folder open (O_DIRECTORY | O_NOFOLLOW) while it lives: every file rtbench
// writes into it, between two checks too, is created and renamed relative to that descriptor
// (writers.h holdFolder), so a swap between a check and a write redirects nothing either.
class FolderIdentity {
public:
    explicit FolderIdentity(std::string folder);  // throws unless `folder` is a real folder
    ~FolderIdentity();
    FolderIdentity(const FolderIdentity&) = delete;
    FolderIdentity& operator=(const FolderIdentity&) = delete;
    const std::string& path() const { return folder_; }
    void check() const;  // throws rtbench::Error naming the folder when the path names another
private:
    std::string folder_;
    unsigned long long device_ = 0, inode_ = 0;
    int fd_ = -1;
};

// Throws rtbench::Error when the results folder is a symlink or holds one: rtbench writes only
// regular files of its own in it, and a planted link (runs.csv -> ~/.bashrc) must not redirect
// a write.
void refuseSymlinks(const std::string& folder);

// Throws rtbench::Error unless `path` is absent or a regular file (not a symlink) that can be
// replaced (checked before a run is computed, so a result is never computed and then lost).
void checkWritableFile(const std::string& path);

// Throws rtbench::Error naming their pids when rtbench processes are writing `folder` now (holding
// a lock of it exclusively: a whole-plan run, a shard, a merge or a retime). Reads only: check and
// compare (`command`) ask it so as never to judge a folder half-written.
void refuseFolderBeingWritten(const std::string& folder, const std::string& command);

// A private scratch folder in the temporary directory (mkdtemp: a name no one else can have
// planted), removed with all it holds when it goes: where check and retime re-run a folder's runs.
class ScratchFolder {
public:
    explicit ScratchFolder(const std::string& stem);  // "<tmp>/<stem>-XXXXXX"
    ~ScratchFolder();
    ScratchFolder(const ScratchFolder&) = delete;
    ScratchFolder& operator=(const ScratchFolder&) = delete;
    const std::string& path() const { return path_; }
private:
    std::string path_;
};

// "<folder>/superseded-<UTC time>[-k]-": the prefix of what one invocation sets aside (rows,
// samples, the context they were run under, their per-run files), names merge and resume never
// read, and the start of no existing file's name.
std::string supersededPrefix(const std::string& folder);

}  // namespace rtbench
