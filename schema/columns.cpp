#include "columns.h"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace rtbench {

const char* columnKindName(ColumnKind kind) {
    switch (kind) {
        case ColumnKind::Parameter:
            return "parameter";
        case ColumnKind::Exact:
            return "exact";
        case ColumnKind::Reference:
            return "reference";
        case ColumnKind::Timing:
            return "timing";
        case ColumnKind::Context:
            return "context";
        case ColumnKind::Scheduled:
            return "scheduled";
    }
    return "?";
}

std::string paramColumn(const std::string& key) {
    std::string column = key;
    for (char& c : column)
        if (c == '.') c = '_';
    return column;
}

std::string formatNumber(double value, int significant) {
    std::ostringstream s;
    s.precision(significant);
    s << value;
    return s.str();
}

}  // namespace rtbench
