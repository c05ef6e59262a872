#include "harness/unpack.h"

#include <archive.h>
#include <archive_entry.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <functional>
#include <map>
#include <regex>
#include <set>

#include "core/error.h"
#include "core/text.h"
#include "harness/writers.h"

namespace rtbench {
namespace {

// One entry the checks let through: a folder (CONFIG, or the archive's root: no parts) or a file
// CONFIG/FILE of `bytes` bytes.
struct Entry {
    std::vector<std::string> parts;
    bool folder = false;
    std::uint64_t bytes = 0;
    std::string name() const { return parts.empty() ? "." : parts.size() == 1 ? parts[0] : parts[0] + "/" + parts[1]; }
    bool operator==(const Entry&) const = default;
};

// The entry named as the archive stores it, control characters escaped.
class Refused : public Error {
public:
    Refused(const std::string& entry, const std::string& why) : Error("'" + printable(entry) + "': " + why) {}
};


// A descriptor closed when it goes out of scope.
struct Fd {
    int fd = -1;
    explicit Fd(int f) : fd(f) {}
    ~Fd() { if (fd >= 0) ::close(fd); }
    Fd(const Fd&) = delete;
    Fd& operator=(const Fd&) = delete;
};

std::string systemError() { return std::strerror(errno); }

std::string archiveError(archive* a) {
    const char* text = archive_error_string(a);
    return text ? text : "(no reason given)";
}

// The archive read from an open descriptor, from its start, as libarchive walks it.
class ArchiveReader {
public:
    explicit ArchiveReader(int fd) : a_(archive_read_new()) {
        if (!a_) throw Error("libarchive: out of memory");
        archive_read_support_filter_gzip(a_);
        archive_read_support_filter_xz(a_);
        archive_read_support_format_tar(a_);
        if (::lseek(fd, 0, SEEK_SET) != 0 || archive_read_open_fd(a_, fd, 1 << 16) != ARCHIVE_OK) {
            const std::string why = "not a readable tar archive: " + archiveError(a_);
            archive_read_free(a_);
            throw Error(why);
        }
    }
    ~ArchiveReader() { archive_read_free(a_); }
    ArchiveReader(const ArchiveReader&) = delete;
    ArchiveReader& operator=(const ArchiveReader&) = delete;
    // The next entry; null at the archive's end.
    archive_entry* next() {
        archive_entry* entry = nullptr;
        const int status = archive_read_next_header(a_, &entry);
        if (status == ARCHIVE_EOF) return nullptr;
        if (status != ARCHIVE_OK) throw Error("unreadable: " + archiveError(a_));
        return entry;
    }
    // The current entry's bytes, chunk by chunk; their count. A truncated archive throws.
    std::uint64_t data(const std::function<void(const char*, std::size_t)>& sink) {
        char buffer[1 << 16];
        std::uint64_t total = 0;
        for (la_ssize_t n; (n = archive_read_data(a_, buffer, sizeof buffer)) != 0;) {
            if (n < 0) throw Error("unreadable: " + archiveError(a_));
            sink(buffer, std::size_t(n));
            total += std::uint64_t(n);
        }
        return total;
    }

private:
    archive* a_;
};

// The entry's path as plain names (a leading "./" dropped); refuses absolute, '..', odd or deep paths.
std::vector<std::string> plainParts(const std::string& path) {
    static const std::regex plain("[A-Za-z0-9_-][A-Za-z0-9._-]{0,254}");
    if (path.empty() || path[0] == '/' || path.find('\\') != std::string::npos || path.find('\0') != std::string::npos)
        throw Refused(path, "an absolute, empty or odd path");
    std::vector<std::string> parts;
    for (std::size_t start = 0; start <= path.size();) {
        const std::size_t slash = std::min(path.find('/', start), path.size());
        const std::string part = path.substr(start, slash - start);
        if (part == "..") throw Refused(path, "'..' leaves the folder");
        if (!part.empty() && part != ".") {
            if (!std::regex_match(part, plain)) throw Refused(path, "'" + printable(part) + "' is not a plain name");
            parts.push_back(part);
        }
        start = slash + 1;
    }
    if (parts.size() > 2) throw Refused(path, "deeper than CONFIG/FILE");
    return parts;
}

// What kind of entry this is, when not a folder or regular file; empty when it is one.
std::string specialKind(archive_entry* entry) {
    if (archive_entry_hardlink(entry)) return "a hard link";
    switch (archive_entry_filetype(entry)) {
        case AE_IFDIR:
        case AE_IFREG:
            return archive_entry_sparse_count(entry) > 0 ? "a sparse file" : "";
        case AE_IFLNK: return "a symbolic link";
        case AE_IFCHR: return "a character device";
        case AE_IFBLK: return "a block device";
        case AE_IFIFO: return "a FIFO";
        case AE_IFSOCK: return "a socket";
        default: return "a special entry";
    }
}

// The entry's checks but its size: type, path, mode.
Entry checkedEntry(archive_entry* entry) {
    const char* raw = archive_entry_pathname(entry);
    const std::string path = raw ? raw : "";
    Entry e;
    e.parts = plainParts(path);
    if (const std::string kind = specialKind(entry); !kind.empty()) throw Refused(path, kind);
    e.folder = archive_entry_filetype(entry) == AE_IFDIR;
    const mode_t mode = archive_entry_perm(entry);
    if (mode & (S_ISUID | S_ISGID | S_ISVTX | S_IWOTH)) {
        char octal[8];
        std::snprintf(octal, sizeof octal, "%04o", unsigned(mode & 07777));
        throw Refused(path, std::string("mode ") + octal + ": setuid, setgid, sticky or world-writable");
    }
    if (e.folder && e.parts.size() == 2) throw Refused(path, "a folder inside a config's folder");
    if (!e.folder && e.parts.size() != 2) throw Refused(path, "a file outside a config's folder");
    return e;
}

// Pass one: every entry read and checked, its bytes counted against the caps; nothing written.
std::vector<Entry> checkArchive(int fd, const UnpackLimits& limits) {
    ArchiveReader reader(fd);
    std::vector<Entry> plan;
    std::map<std::string, bool> seen;  // name -> folder
    std::uint64_t total = 0;
    std::set<std::string> configs;  // the config folders, given as entries or as the folders of files
    while (archive_entry* entry = reader.next()) {
        Entry e = checkedEntry(entry);
        if (plan.size() == limits.entries) throw Refused(e.name(), "over " + std::to_string(limits.entries) + " entries");
        if (!e.parts.empty() && configs.insert(e.parts[0]).second && configs.size() > limits.folders)
            throw Refused(e.name(), "over " + std::to_string(limits.folders) + " config folders");
        const auto [it, fresh] = seen.emplace(e.name(), e.folder);
        if (!fresh && !(it->second && e.folder)) throw Refused(e.name(), "a second entry of this name");
        const la_int64_t declared = archive_entry_size_is_set(entry) ? archive_entry_size(entry) : -1;
        e.bytes = reader.data([&](const char*, std::size_t n) {
            total += n;
            if (total > limits.totalBytes)
                throw Refused(e.name(), "the archive unpacks to over " + std::to_string(limits.totalBytes) + " bytes");
        });
        if (e.bytes > limits.fileBytes)
            throw Refused(e.name(), std::to_string(e.bytes) + " bytes, over the " + std::to_string(limits.fileBytes) +
                                        "-byte cap of a file");
        if (declared >= 0 && std::uint64_t(declared) != e.bytes)
            throw Refused(e.name(), "its header says " + std::to_string(declared) + " bytes; it holds " + std::to_string(e.bytes));
        if (e.folder && e.bytes) throw Refused(e.name(), "a folder with contents");
        plan.push_back(std::move(e));
    }
    return plan;
}

// `dir` as a held folder: made 0755 when absent, refused when a link or not a folder.
int holdTarget(const std::string& dir) {
    struct stat st {};
    if (::lstat(dir.c_str(), &st) != 0) {
        if (errno != ENOENT || ::mkdir(dir.c_str(), 0755) != 0) throw Error(dir + ": cannot make the folder: " + systemError());
    } else if (S_ISLNK(st.st_mode)) {
        throw Error(dir + ": is a symbolic link; refusing to unpack through it");
    } else if (!S_ISDIR(st.st_mode)) {
        throw Error(dir + ": exists and is not a folder");
    }
    const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0) throw Error(dir + ": cannot open the folder: " + systemError());
    return fd;
}

// Pass two's state: the config folders held (made 0755 when absent), the temporaries written.
// Until commit(), the destructor removes every temporary and every folder it made.
class Staging {
public:
    Staging(std::string dir, int dirFd) : dir_(std::move(dir)), dirFd_(dirFd) {}
    ~Staging() {
        if (committed_) return;
        for (const auto& t : temporaries_) ::unlinkat(folders_.at(t.config)->fd, t.temporary.c_str(), 0);
        for (const std::string& made : made_) ::unlinkat(dirFd_, made.c_str(), AT_REMOVEDIR);
    }
    int folder(const std::string& config) {
        if (auto it = folders_.find(config); it != folders_.end()) return it->second->fd;
        if (::mkdirat(dirFd_, config.c_str(), 0755) == 0) made_.push_back(config);
        else if (errno != EEXIST) throw Error(dir_ + "/" + config + ": cannot make the folder: " + systemError());
        const int fd = ::openat(dirFd_, config.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
        if (fd < 0) throw Error(dir_ + "/" + config + ": is a symbolic link or not a folder; refusing to unpack into it");
        return folders_.emplace(config, std::make_unique<Fd>(fd)).first->second->fd;
    }
    // A new temporary for CONFIG/FILE, 0644, never an existing file or link.
    int create(const Entry& e) {
        const int folderFd = folder(e.parts[0]);
        const std::string temporary =
            ".unpack-" + std::to_string(::getpid()) + "-" + std::to_string(temporaries_.size()) + ".tmp";  // never a FILE name
        const int fd = ::openat(folderFd, temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
        if (fd < 0) throw Error(dir_ + "/" + e.parts[0] + "/" + temporary + ": cannot create: " + systemError());
        temporaries_.push_back({e.parts[0], temporary, e.parts[1]});
        if (::fchmod(fd, 0644) != 0) {
            ::close(fd);
            throw Error(dir_ + "/" + e.name() + ": cannot set its mode: " + systemError());
        }
        return fd;
    }
    // Every temporary renamed over its name, once every name is checked to be free or a regular
    // file (a folder or anything else there refuses the whole unpack before any rename).
    void commit() {
        for (const auto& t : temporaries_) {
            struct stat st {};
            if (::fstatat(folders_.at(t.config)->fd, t.name.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0 && !S_ISREG(st.st_mode))
                throw Error(dir_ + "/" + t.config + "/" + t.name + ": exists and is not a regular file; refusing to replace it");
        }
        for (const auto& t : temporaries_) {
            const int fd = folders_.at(t.config)->fd;
            if (::renameat(fd, t.temporary.c_str(), fd, t.name.c_str()) != 0)
                throw Error(dir_ + "/" + t.config + "/" + t.name + ": cannot put in place: " + systemError());
        }
        committed_ = true;
    }

private:
    struct Temporary { std::string config, temporary, name; };
    std::string dir_;
    int dirFd_;
    std::map<std::string, std::unique_ptr<Fd>> folders_;
    std::vector<Temporary> temporaries_;
    std::vector<std::string> made_;
    bool committed_ = false;
};

// Pass two: the archive read again, each entry equal to pass one's, each file to a temporary;
// all renamed into place at the end.
void writeArchive(int fd, const std::vector<Entry>& plan, const std::string& dir, int dirFd) {
    ArchiveReader reader(fd);
    Staging staging(dir, dirFd);
    std::size_t i = 0;
    for (archive_entry* entry; (entry = reader.next()) != nullptr; ++i) {
        Entry e = checkedEntry(entry);
        if (i >= plan.size() || e.parts != plan[i].parts || e.folder != plan[i].folder)
            throw Error("the archive changed while it was unpacked (entry " + std::to_string(i + 1) + ")");
        if (e.folder) {
            if (!e.parts.empty()) staging.folder(e.parts[0]);
            continue;
        }
        const Fd out(staging.create(e));
        const std::string path = dir + "/" + e.name();
        std::uint64_t written = 0;
        e.bytes = reader.data([&](const char* bytes, std::size_t n) {
            if ((written += n) > plan[i].bytes) throw Error("the archive changed while it was unpacked (" + e.name() + ")");
            if (!writeAll(out.fd, std::string_view(bytes, n))) throw Error(path + ": cannot write: " + systemError());
        });
        if (e.bytes != plan[i].bytes) throw Error("the archive changed while it was unpacked (" + e.name() + ")");
        if (::fsync(out.fd) != 0) throw Error(path + ": cannot sync: " + systemError());
    }
    if (i != plan.size()) throw Error("the archive changed while it was unpacked (it ended early)");
    staging.commit();
}

}  // namespace

std::vector<std::string> unpackCampaign(const std::string& archive, const std::string& dir, const UnpackLimits& limits) {
    const Fd in(::open(archive.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC));
    struct stat st {};
    if (in.fd < 0 || ::fstat(in.fd, &st) != 0) throw Error(archive + ": cannot open: " + systemError());
    if (!S_ISREG(st.st_mode)) throw Error(archive + ": not a regular file");
    std::vector<Entry> plan;
    try {
        plan = checkArchive(in.fd, limits);
    } catch (const Error& e) {
        throw Error(archive + ": refused: " + e.what() + "; nothing unpacked");
    }
    const Fd target(holdTarget(dir));
    try {
        writeArchive(in.fd, plan, dir, target.fd);
    } catch (const Error& e) {
        throw Error(archive + ": " + e.what() + "; nothing unpacked");
    }
    std::vector<std::string> files;
    for (const Entry& e : plan)
        if (!e.folder) files.push_back(e.name());
    return files;
}

}  // namespace rtbench
