// The folder an experiment writes: <output>/<experiment.name>/, checked before any run starts
// and held by one process at a time.
#pragma once
#include <string>

namespace rtbench {

// <output>/<name>; throws rtbench::Error unless `name` is a plain folder name (no separator,
// not "." or "..", not absolute, no control characters), so results never land outside `output`.
std::string experimentFolder(const std::string& output, const std::string& name);

// An exclusive lock on a results folder (flock on <folder>/.rtbench.lock, holding the pid), kept
// for the lifetime of the object. A second process fails at once, naming the holder's pid. The
// lock ends with the process, so a killed run never leaves the folder locked.
class OutputFolderLock {
  public:
    explicit OutputFolderLock(const std::string& folder);
    ~OutputFolderLock();
    OutputFolderLock(const OutputFolderLock&) = delete;
    OutputFolderLock& operator=(const OutputFolderLock&) = delete;

  private:
    int fd_ = -1;
};

// Throws rtbench::Error unless `path` is absent or a regular file that can be replaced (checked
// before a run is computed, so a result is never computed and then lost).
void checkWritableFile(const std::string& path);

}  // namespace rtbench
