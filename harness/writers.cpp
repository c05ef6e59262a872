#include "writers.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "structures/error.h"
#include "structures/text.h"

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

void writeFileAtomically(const std::string& path, const std::string& text) {
    const std::string tmp = path + ".tmp";
    std::error_code ec;
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        if (!out) throw Error(tmp + ": cannot open for writing");
        out << text;
        out.flush();
        if (!out) {
            out.close();
            std::filesystem::remove(tmp, ec);  // never leave a partial file behind
            throw Error(tmp + ": write failed (disk full?); " + path + " is unchanged");
        }
    }
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        const std::string why = ec.message();
        std::filesystem::remove(tmp, ec);
        throw Error(path + ": rename failed: " + why);
    }
}

void writeCsv(const std::string& path, const std::vector<std::string>& columns, const std::vector<Row>& rows) {
    const std::set<std::string> declared(columns.begin(), columns.end());
    std::ostringstream out;
    for (std::size_t c = 0; c < columns.size(); ++c) out << (c ? "," : "") << csvField(columns[c]);
    out << "\n";
    for (std::size_t r = 0; r < rows.size(); ++r) {
        for (const auto& [column, value] : rows[r])
            if (!declared.count(column))
                throw Error(path + ": row " + std::to_string(r + 1) + " sets column '" + column +
                            "', which is not declared");
        for (std::size_t c = 0; c < columns.size(); ++c) {
            auto it = rows[r].find(columns[c]);
            out << (c ? "," : "") << (it == rows[r].end() ? "" : csvField(it->second));
        }
        out << "\n";
    }
    writeFileAtomically(path, out.str());
}

namespace {
struct CsvRecords {
    std::vector<std::vector<std::string>> records;
    std::vector<std::size_t> lines;  // line where each record starts
};

CsvRecords readCsvRecords(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path + ": cannot open CSV");
    std::stringstream buffer;
    buffer << in.rdbuf();
    const std::string text = buffer.str();
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
    if (!field.empty() || fieldWasQuoted || !record.empty()) {
        record.push_back(std::move(field));
        out.records.push_back(std::move(record));
        out.lines.push_back(recordLine);
    }
    return out;
}
}  // namespace

std::vector<Row> readCsv(const std::string& path) {
    const CsvRecords csv = readCsvRecords(path);
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

Json readJson(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path + ": cannot open");
    try {
        return Json::parse(in);
    } catch (const Json::exception& e) {
        throw Error(path + ": not valid JSON: " + e.what());
    }
}


}  // namespace rtbench
