// The error convention of every library function that can fail on its input (README,
// Conventions): it returns false (or nullopt) and fills `error` with the file and the problem.
#pragma once
#include <string>
#include <utility>

namespace mf {

// `return fail(error, "FILE: what is wrong");`
inline bool fail(std::string& error, std::string message) {
    error = std::move(message);
    return false;
}

}  // namespace mf
