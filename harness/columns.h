// The columns of runs.csv, each declared once with its kind and unit. The kind says how a value
// may differ between two runs of the same config, and so how `rtbench check` compares it:
//   parameter  a config key or the run's identity: equal by construction;
//   count      deterministic: equal on every machine with the same device (checked exactly);
//   reference  derived from another library's floating point (Embree's ISA path): compared
//              within a declared tolerance, never as an exact count;
//   timing     seconds and rates: reported when outside a relative tolerance, never a failure;
//   context    where and when (commit, device, driver, Embree's threads and ISA): reported.
#pragma once
#include <string>
#include <vector>

#include "schema/columns.h"
#include "writers.h"

namespace rtbench {

// Every column of runs.csv in order: one per config key (kind parameter), then the metrics.
const std::vector<ColumnSpec>& runColumnSpecs();
std::vector<std::string> runColumns();

// The spec of a column; throws rtbench::Error naming the column when it is not declared.
const ColumnSpec& columnSpec(const std::string& name);

// Reads a runs CSV (runs.csv or a shard's) and checks it is whole: its header holds the declared
// columns of one results schema (ColumnSpec::since: a file of an older schema lacks the later
// columns, and its rows lack those keys), and every row has a run number, unique in the file. Throws rtbench::Error
// naming the file and the missing or unknown column, or the row and run.
// `schema`, when given, gets the file's results schema (kSchemaVersion for a file without rows).
std::vector<Row> readRunsCsv(const std::string& path, int* schema = nullptr);
std::vector<Row> parseRunsCsv(const std::string& text, const std::string& path, int* schema = nullptr);

// What a column's cells hold, for readers that type them (pandas: Int64, float64, boolean,
// string): integer, number (inf and nan included), boolean ("true"/"false") or text: the
// column's ColumnSpec::type (a config key's column has its key's type; a column that names or
// explains declares text where it is declared; the rest are inferred from the unit, schema/columns.h).
// Empty cells (a column a run does not write) are missing values of any type.
const char* columnValueType(const ColumnSpec& column);

// The column dictionary written beside runs.csv as columns.csv (and by `rtbench columns --csv`):
// every column, config keys included, with its kind, value type, unit, the schema that added it,
// when a run writes it, and its meaning.
std::string columnsCsv();

// A results folder's schema (schema/columns.h kSchemaVersion) as its context.json records it; 1
// when it does not (folders written before the schema was recorded).
int schemaVersion(const Json& context);

// The metric columns (all but the config keys) as a Markdown table: column, kind, value type,
// unit, meaning. docs/columns.md holds this table; a test keeps the two equal.
std::string columnsMarkdown();

}  // namespace rtbench
