// The message of the rtbench::Error that f() throws, or "(no error)": for tests that assert what
// an error says.
#pragma once
#include <string>

#include "core/error.h"

namespace rtbench {

std::string errorOf(auto&& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "(no error)";
}

}  // namespace rtbench
