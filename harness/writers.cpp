#include "writers.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <set>
#include <sstream>

#include "core/error.h"
#include "core/input_file.h"
#include "core/text.h"

namespace rtbench {

namespace {
// A field as RFC 4180 writes it: quoted when it holds a comma, a quote or a line break.
std::string csvField(const std::string& raw) {
    const std::string s = validUtf8(raw);
    if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
    std::string out = "\"";
    for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}
}  // namespace

namespace {

std::string parentOf(const std::string& path) {
    const std::filesystem::path parent = std::filesystem::path(path).parent_path();
    return parent.empty() ? "." : parent.string();
}

// The results folders held open (holdFolder), by their lexically normal path.
std::mutex heldMutex;
std::map<std::string, std::vector<int>> heldFolders;

std::string folderKey(const std::string& folder) {
    std::string key = std::filesystem::path(folder.empty() ? "." : folder).lexically_normal().string();
    while (key.size() > 1 && key.back() == '/') key.pop_back();
    return key;
}

// The folder a write goes into: the held descriptor of its parent when it is a held results
// folder (owned = false), else the parent opened now.
struct Folder {
    int fd = -1;
    bool owned = false;
    Folder(const Folder&) = delete;
    Folder& operator=(const Folder&) = delete;
    explicit Folder(const std::string& path) {
        const std::string parent = parentOf(path);
        {
            std::lock_guard<std::mutex> lock(heldMutex);
            const auto it = heldFolders.find(folderKey(parent));
            if (it != heldFolders.end() && !it->second.empty()) fd = it->second.back();
        }
        if (fd >= 0) return;
        fd = ::open(parent.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
        if (fd < 0) throw Error(path + ": cannot open its folder: " + std::strerror(errno));
        owned = true;
    }
    ~Folder() {
        if (owned) ::close(fd);
    }
};

std::string nameOf(const std::string& path) { return std::filesystem::path(path).filename().string(); }

void refuseSymlinkAt(const Folder& dir, const std::string& path) {
    struct stat st{};
    if (::fstatat(dir.fd, nameOf(path).c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0 && S_ISLNK(st.st_mode))
        throw Error(path + ": is a symlink; rtbench never writes through one: remove it");
}

// A new file of a unique name in `dir` (O_CREAT | O_EXCL | O_NOFOLLOW: never a planted file or
// link), mode 0666 & ~umask as open(2) makes it: its descriptor, its name in `name`.
int createTemporaryAt(const Folder& dir, const std::string& stem, std::string& name) {
    static std::atomic<unsigned> counter{0};
    for (int attempt = 0; attempt < 100; ++attempt) {
        name = "." + stem + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
        const int fd = ::openat(dir.fd, name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
        if (fd >= 0 || errno != EEXIST) return fd;
    }
    errno = EEXIST;
    return -1;
}


}  // namespace

// Writes all of `bytes` to fd; false (errno set) on failure.
bool writeAll(int fd, std::string_view bytes) {
    std::size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            if (n == 0) errno = ENOSPC;
            return false;
        }
        done += std::size_t(n);
    }
    return true;
}

void holdFolder(const std::string& folder, int fd) {
    std::lock_guard<std::mutex> lock(heldMutex);
    heldFolders[folderKey(folder)].push_back(fd);
}

void releaseFolder(const std::string& folder, int fd) {
    std::lock_guard<std::mutex> lock(heldMutex);
    auto& fds = heldFolders[folderKey(folder)];
    fds.erase(std::remove(fds.begin(), fds.end(), fd), fds.end());
    if (fds.empty()) heldFolders.erase(folderKey(folder));
}

void writeFileAtomically(const std::string& path, const std::string& text) {
    // A temporary of a unique name beside the target, renamed over it: rename replaces the
    // directory entry, never writing through what was there. Every step is relative to the
    // folder's descriptor (held for a results folder), so a folder renamed or swapped for a link
    // meanwhile redirects nothing.
    const Folder dir(path);
    refuseSymlinkAt(dir, path);
    std::string tmp;
    const int fd = createTemporaryAt(dir, nameOf(path), tmp);
    if (fd < 0) throw Error(path + ": cannot create a temporary file beside it: " + std::strerror(errno));
    const bool written = writeAll(fd, text) && ::fsync(fd) == 0;
    const int why = errno;
    if (::close(fd) != 0 || !written) {
        ::unlinkat(dir.fd, tmp.c_str(), 0);  // never leave a partial file behind
        throw Error(parentOf(path) + "/" + tmp + ": write failed (disk full?): " + std::strerror(written ? errno : why) +
                    "; " + path + " is unchanged");
    }
    if (::renameat(dir.fd, tmp.c_str(), dir.fd, nameOf(path).c_str()) != 0) {
        const int renameWhy = errno;
        ::unlinkat(dir.fd, tmp.c_str(), 0);
        throw Error(path + ": rename failed: " + std::strerror(renameWhy));
    }
    ::fsync(dir.fd);  // the rename itself, synced: the folder's entry
}

namespace {

// One CSV line of `row` under `columns`; `rowNumber` names it in the error for an undeclared column.
std::string csvLine(const std::string& path, const std::vector<std::string>& columns,
                    const std::set<std::string>& declared, const Row& row, std::size_t rowNumber) {
    for (const auto& [column, value] : row)
        if (!declared.count(column))
            throw Error(path + ": row " + std::to_string(rowNumber) + " sets column '" + column +
                        "', which is not declared");
    std::string line;
    for (std::size_t c = 0; c < columns.size(); ++c) {
        auto it = row.find(columns[c]);
        line += (c ? "," : "") + (it == row.end() ? std::string() : csvField(it->second));
    }
    return line + "\n";
}

}  // namespace

std::string cellText(const Row& row, const std::string& column) {
    const auto it = row.find(column);
    return it == row.end() ? std::string() : it->second;
}

double cellNumber(const std::string& cell) {
    char* end = nullptr;
    const double v = std::strtod(cell.c_str(), &end);
    return cell.empty() || *end != '\0' ? std::nan("") : v;
}

std::string csvText(const std::string& name, const std::vector<std::string>& columns, const std::vector<Row>& rows) {
    const std::set<std::string> declared(columns.begin(), columns.end());
    std::string out;
    for (std::size_t c = 0; c < columns.size(); ++c) out += (c ? "," : "") + csvField(columns[c]);
    out += "\n";
    for (std::size_t r = 0; r < rows.size(); ++r) out += csvLine(name, columns, declared, rows[r], r + 1);
    return out;
}

void writeCsv(const std::string& path, const std::vector<std::string>& columns, const std::vector<Row>& rows) {
    writeFileAtomically(path, csvText(path, columns, rows));
}

void appendCsvRow(const std::string& path, const std::vector<std::string>& columns, const Row& row) {
    appendCsvRows(path, columns, {row});
}

void appendCsvRows(const std::string& path, const std::vector<std::string>& columns, const std::vector<Row>& rows) {
    const std::set<std::string> declared(columns.begin(), columns.end());
    std::string line;
    for (std::size_t r = 0; r < rows.size(); ++r) line += csvLine(path, columns, declared, rows[r], r + 1);
    const Folder dir(path);
    const int fd = ::openat(dir.fd, nameOf(path).c_str(), O_WRONLY | O_APPEND | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0) {
        if (errno == ELOOP) throw Error(path + ": is a symlink; rtbench never writes through one: remove it");
        throw Error(path + ": cannot open to append a row: " + std::strerror(errno));
    }
    struct stat st{};
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        ::close(fd);
        throw Error(path + ": not a regular file");
    }
    // One write of the whole line; on failure the file is cut back to what it was.
    const bool written = writeAll(fd, line) && ::fdatasync(fd) == 0;
    const int why = errno;
    if (!written) {
        const bool restored = ::ftruncate(fd, st.st_size) == 0;
        ::close(fd);
        throw Error(path + ": write failed (disk full?): " + std::strerror(why) + "; " +
                    (restored ? "the file is as before these rows" : "and could not be cut back to its rows"));
    }
    ::close(fd);
}

namespace {
struct CsvRecords {
    std::vector<std::vector<std::string>> records;
    std::vector<std::size_t> lines;  // line where each record starts
};

CsvRecords parseCsvRecords(const std::string& text, const std::string& path) {
    // RFC 4180: records end in CRLF or LF; a quoted field may hold commas, line breaks and "".
    CsvRecords out;
    std::vector<std::string> record;
    std::string field;
    std::size_t line = 1, quoteLine = 0, recordLine = 1;
    bool quoted = false, fieldWasQuoted = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (quoted) {
            if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
                field += '"';
                ++i;
            } else if (c == '"') {
                quoted = false;
            } else {
                line += c == '\n';
                field += c;
            }
            continue;
        }
        if (c == '"') {
            if (!field.empty() || fieldWasQuoted)
                throw Error(path + ":" + std::to_string(line) + ": a quote inside an unquoted field");
            quoted = fieldWasQuoted = true;
            quoteLine = line;
        } else if (c == ',') {
            record.push_back(std::move(field));
            field.clear();
            fieldWasQuoted = false;
        } else if (c == '\n' || (c == '\r' && i + 1 < text.size() && text[i + 1] == '\n')) {
            if (c == '\r') ++i;
            record.push_back(std::move(field));
            out.records.push_back(std::move(record));
            out.lines.push_back(recordLine);
            record.clear();
            field.clear();
            fieldWasQuoted = false;
            recordLine = ++line;
        } else {
            if (fieldWasQuoted)
                throw Error(path + ":" + std::to_string(line) + ": text after a closing quote");
            field += c;
        }
    }
    if (quoted) throw Error(path + ":" + std::to_string(quoteLine) + ": a quoted field is never closed");
    // rtbench ends every row with a line end: a last row without one was cut while written.
    if (!field.empty() || fieldWasQuoted || !record.empty())
        throw Error(path + ":" + std::to_string(recordLine) + ": the last row has no line end (cut while written?)");
    return out;
}
}  // namespace

std::vector<Row> readCsv(const std::string& path) {
    return parseCsv(readInputFile(path, kMaxResultsFileBytes, "CSV file"), path);
}

std::vector<Row> parseCsv(const std::string& text, const std::string& path) {
    const CsvRecords csv = parseCsvRecords(text, path);
    const auto& records = csv.records;
    std::vector<Row> rows;
    if (records.empty()) throw Error(path + ": empty CSV (no header)");
    const std::vector<std::string>& header = records[0];
    std::set<std::string> names;
    for (const std::string& name : header)
        if (!names.insert(name).second) throw Error(path + ": column '" + name + "' appears twice in the header");
    for (std::size_t r = 1; r < records.size(); ++r) {
        if (records[r].size() != header.size())
            throw Error(path + ":" + std::to_string(csv.lines[r]) + ": row " + std::to_string(r) + " has " + std::to_string(records[r].size()) +
                        " of the header's " + std::to_string(header.size()) + " fields (cut or joined row?)");
        Row row;
        for (std::size_t c = 0; c < header.size(); ++c) row[header[c]] = records[r][c];
        rows.push_back(std::move(row));
    }
    return rows;
}

void writeJson(const std::string& path, const Json& json) {
    // Invalid UTF-8 (a mesh name, an error quoting a file) is replaced rather than refused.
    writeFileAtomically(path, json.dump(2, ' ', false, Json::error_handler_t::replace) + "\n");
}

Json readJson(const std::string& path) { return parseJson(readInputFile(path, kMaxResultsFileBytes, "JSON file"), path); }

Json parseJson(const std::string& text, const std::string& path) {
    try {
        return Json::parse(text);
    } catch (const Json::exception& e) {
        throw Error(path + ": not valid JSON: " + e.what());
    }
}


}  // namespace rtbench
