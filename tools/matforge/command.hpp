// Subcommand registry: each cmd_*.cpp registers itself; main() parses and runs the chosen one.
// Exit codes are decided in tools/ only (docs/interface.md, "Exit codes"); the library returns
// results and findings. Every message a command prints starts with "matforge <command>: ".
#pragma once
#include <CLI/CLI.hpp>
#include <functional>
#include <iostream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/text.hpp"
#include "findings/findings.hpp"
#include "validate/verdict.hpp"

namespace mf::cli {

enum class ExitCode : int {
    ok = 0,                  // done; no finding at or above --fail-on
    findings = 1,            // a finding at or above --fail-on, or an input not processed / an output not written
    usage = 2,               // a usage or configuration error: option, preset, rules, scene, manifest, no Vulkan device
    interrupted_int = 130,   // stopped by SIGINT (128 + 2), cleanly: no temporary, no stale manifest
    interrupted_term = 143,  // stopped by SIGTERM (128 + 15)
};

struct Command {
    std::string name;
    int order;  // position in --help
    // Adds the subcommand's options to `sub`; returns the function to run after parsing.
    std::function<std::function<ExitCode()>(CLI::App& sub)> setup;
    std::string description;
};

std::vector<Command>& registry();

struct Register {
    explicit Register(Command c) { registry().push_back(std::move(c)); }
};

// "matforge <command>: <message>" on stderr ("matforge: " without a command), control
// characters escaped: a file name holding ESC or BEL never reaches the terminal raw.
inline void say(std::string_view command, const std::string& message) {
    std::cerr << "matforge" << (command.empty() ? "" : " ") << command << ": " << terminal_safe(message, true) << "\n";
}
// say() and return `code`: the shape of every early exit.
inline ExitCode fail(std::string_view command, const std::string& message, ExitCode code = ExitCode::usage) {
    say(command, message);
    return code;
}

// The exit code of a run's verdict (validate::run_fails decides it).
inline ExitCode verdict_exit(bool run_fails) { return run_fails ? ExitCode::findings : ExitCode::ok; }

}  // namespace mf::cli
