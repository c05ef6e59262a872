// A run's warnings: one text cell of its row, each warning after the last, "; " between them.
#pragma once
#include <string>

#include "schema/columns.h"

namespace rtbench {

inline void addWarning(Row& row, const std::string& warning) {
    std::string& cell = row["warnings"];
    cell += (cell.empty() ? "" : "; ") + warning;
}

}  // namespace rtbench
