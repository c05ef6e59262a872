#include "writers.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "structures/error.h"

namespace rtbench {

namespace {
std::string csvField(const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string out = "\"";
    for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}
}  // namespace

void writeFileAtomically(const std::string& path, const std::string& text) {
    const std::string tmp = path + ".tmp";
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        if (!out) throw Error(tmp + ": cannot open for writing");
        out << text;
        out.flush();
        if (!out) throw Error(tmp + ": write failed (disk full?)");
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) throw Error(path + ": rename failed: " + ec.message());
}

void writeCsv(const std::string& path, const std::vector<std::string>& columns, const std::vector<Row>& rows) {
    std::ostringstream out;
    for (std::size_t c = 0; c < columns.size(); ++c) out << (c ? "," : "") << csvField(columns[c]);
    out << "\n";
    for (const Row& row : rows) {
        for (std::size_t c = 0; c < columns.size(); ++c) {
            auto it = row.find(columns[c]);
            out << (c ? "," : "") << (it == row.end() ? "" : csvField(it->second));
        }
        out << "\n";
    }
    writeFileAtomically(path, out.str());
}

std::vector<Row> readCsv(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path + ": cannot open CSV");
    std::vector<std::vector<std::string>> records;
    std::vector<std::string> record;
    std::string field;
    bool quoted = false, any = false;
    char c;
    while (in.get(c)) {
        any = true;
        if (quoted) {
            if (c == '"') {
                if (in.peek() == '"') field += static_cast<char>(in.get());
                else quoted = false;
            } else {
                field += c;
            }
        } else if (c == '"') {
            quoted = true;
        } else if (c == ',') {
            record.push_back(field);
            field.clear();
        } else if (c == '\n') {
            record.push_back(field);
            records.push_back(record);
            record.clear();
            field.clear();
            any = false;
        } else {
            field += c;
        }
    }
    if (any) {
        record.push_back(field);
        records.push_back(record);
    }
    std::vector<Row> rows;
    if (records.empty()) return rows;
    for (std::size_t r = 1; r < records.size(); ++r) {
        Row row;
        for (std::size_t c = 0; c < records[0].size() && c < records[r].size(); ++c) row[records[0][c]] = records[r][c];
        rows.push_back(row);
    }
    return rows;
}

std::string jsonString(const std::string& s) {
    std::string out = "\"";
    for (char c : s) {
        switch (c) {
            case '"': out += "\\\""; break;
            case '\\': out += "\\\\"; break;
            case '\n': out += "\\n"; break;
            case '\t': out += "\\t"; break;
            case '\r': out += "\\r"; break;
            default:
                if (static_cast<unsigned char>(c) < 0x20) {
                    char buf[8];
                    std::snprintf(buf, sizeof buf, "\\u%04x", c);
                    out += buf;
                } else {
                    out += c;
                }
        }
    }
    return out + "\"";
}

std::string formatNumber(double value, int significant) {
    std::ostringstream s;
    s.precision(significant);
    s << value;
    return s.str();
}

}  // namespace rtbench
