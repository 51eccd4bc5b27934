// Subcommand registry: each cmd_*.cpp registers itself; main() parses and runs the chosen one.
// Exit codes (shared/spec/interface.md): 0 done, 1 findings at/above --fail-on or inputs not
// processed, 2 usage or configuration error.
#pragma once
#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

namespace mf::cli {

enum Exit : int { kExitOk = 0, kExitFindings = 1, kExitUsage = 2 };

struct Command {
    std::string name;
    int order;  // position in --help
    // Adds the subcommand's options to `sub`; returns the function to run after parsing.
    std::function<std::function<int()>(CLI::App& sub)> setup;
    std::string description;
};

std::vector<Command>& registry();

struct Register {
    explicit Register(Command c) { registry().push_back(std::move(c)); }
};

}  // namespace mf::cli
