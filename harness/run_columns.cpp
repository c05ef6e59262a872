#include "run_columns.h"

namespace rtbench {

const RunColumns& runColumnsDeclared() {
    static const RunColumns columns;
    return columns;
}

}  // namespace rtbench
