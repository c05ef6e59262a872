// Result writers: the per-experiment CSV (one row per run, rewritten atomically after every
// run so an interrupted sweep leaves a complete file) and small JSON helpers.
#pragma once
#include <map>
#include <string>
#include <vector>

namespace rtbench {

using Row = std::map<std::string, std::string>;

// Writes `rows` under `columns` (missing cells empty) to path via path.tmp + rename.
void writeCsv(const std::string& path, const std::vector<std::string>& columns, const std::vector<Row>& rows);

// Reads a CSV written by writeCsv (quoted fields with "" escapes) into rows keyed by header.
std::vector<Row> readCsv(const std::string& path);

// Writes text to path via path.tmp + rename.
void writeFileAtomically(const std::string& path, const std::string& text);

std::string jsonString(const std::string& s);  // quoted, escaped

std::string formatNumber(double value, int significant = 6);

}  // namespace rtbench
