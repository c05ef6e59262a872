// Result writers: the per-experiment CSV (one row per run, rewritten atomically after every
// run so an interrupted sweep leaves a complete file) JSON files.
#pragma once
#include <nlohmann/json.hpp>

#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "schema/columns.h"

namespace rtbench {

// The value of a numeric cell as rtbench writes it; NaN for an empty or text cell.
double cellNumber(const std::string& cell);
// A row's cell, "" when the row lacks the column (a folder of an older schema).
std::string cellText(const Row& row, const std::string& column);

// Writes `rows` under `columns` (missing cells empty) to path atomically (writeFileAtomically); a
// row that sets a column not in `columns` is an error (a typo never silently drops a value).
void writeCsv(const std::string& path, const std::vector<std::string>& columns, const std::vector<Row>& rows);
// The text writeCsv writes (`name` names the file in errors).
std::string csvText(const std::string& name, const std::vector<std::string>& columns, const std::vector<Row>& rows);

// Appends one row to an existing CSV written by writeCsv with the same columns: one write of the
// whole line (O_APPEND, never through a symlink), synced; a failed write (a full disk) cuts the
// file back to the rows it had. A sweep's per-run cost, whatever the number of rows.
void appendCsvRow(const std::string& path, const std::vector<std::string>& columns, const Row& row);
// The same for several rows, in one write.
void appendCsvRows(const std::string& path, const std::vector<std::string>& columns, const std::vector<Row>& rows);

// Reads a CSV as RFC 4180 (quoted fields with "" escapes and line breaks, LF or CRLF) into rows
// keyed by the header. Throws rtbench::Error naming the file and line on an unclosed quote, a
// duplicated header name, a row with more or fewer fields than the header, or a last row without
// a line end (rtbench ends every row with one: such a row was cut while written).
std::vector<Row> readCsv(const std::string& path);
// The same on a file's text (`path` names it in errors).
std::vector<Row> parseCsv(const std::string& text, const std::string& path);

// Writes text to path through a uniquely named temporary beside it (created with O_EXCL, so
// never a planted file or symlink), synced and renamed over path; refuses a path that is a
// symlink. On failure the temporary is removed and path unchanged.
void writeFileAtomically(const std::string& path, const std::string& text);

// Writes all of `bytes` to fd, through short writes and EINTR; false (errno set) on failure.
bool writeAll(int fd, std::string_view bytes);

// A results folder held open (output_folder.h FolderIdentity, O_DIRECTORY | O_NOFOLLOW): while
// held, writeFileAtomically and appendCsvRows into it (a path whose parent is `folder`) create,
// write and rename relative to `fd`, never through the path, so a folder renamed away and
// replaced by a link mid-run receives nothing.
void holdFolder(const std::string& folder, int fd);
void releaseFolder(const std::string& folder, int fd);

// JSON files (nlohmann::json, keys kept in the order written): written atomically; a read that
// fails names the file. CSV and JSON files are read only when regular and within
// kMaxResultsFileBytes (core/input_file.h).
using Json = nlohmann::ordered_json;
void writeJson(const std::string& path, const Json& json);
Json readJson(const std::string& path);
Json parseJson(const std::string& text, const std::string& path);  // `path` names it in errors

}  // namespace rtbench
