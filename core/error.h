// The one exception type of rtbench: a message a user can act on (file, line, key, limits).
#pragma once
#include <stdexcept>
#include <string>

namespace rtbench {

struct Error : std::runtime_error {
    using std::runtime_error::runtime_error;
};

}  // namespace rtbench
