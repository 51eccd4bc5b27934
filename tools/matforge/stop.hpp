// SIGINT and SIGTERM for the commands that write (ingest, validate): the first one asks the run
// to stop (base/interrupt.hpp) and it ends cleanly; a second one ends the process at once (the
// handler is reset, and atomic writes keep every final name complete even then).
#pragma once
#include <csignal>

#include <string>
#include <vector>

#include "base/interrupt.hpp"
#include "command.hpp"
#include "findings/rules.hpp"

namespace mf::cli {

inline void install_stop_handlers() {
    struct sigaction sa {};
    sa.sa_handler = [](int sig) { g_stop_signal.store(sig, std::memory_order_relaxed); };
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESETHAND;  // the second signal takes the default action
    sigaction(SIGINT, &sa, nullptr);
    sigaction(SIGTERM, &sa, nullptr);
}

// The run stopped on a signal: say so, exit 128 + the signal (130 SIGINT, 143 SIGTERM).
inline ExitCode interrupted(std::string_view command, const std::string& what) {
    const int sig = g_stop_signal.load();
    say(command, std::string("interrupted (") + (sig == SIGTERM ? "SIGTERM" : "SIGINT") + "): " + what);
    return sig == SIGTERM ? ExitCode::interrupted_term : ExitCode::interrupted_int;
}

// Suppressions of the rules configuration whose material glob matches none of `names`: a typo
// in a glob must not pass for a silenced finding that is merely absent.
inline void report_unmatched_suppressions(std::string_view command, const rules::RuleConfig& rules,
                                          const std::vector<std::string>& names) {
    for (const auto& s : rules.suppressions) {
        bool matched = false;
        for (const auto& n : names) matched = matched || rules::glob_match(s.material, n);
        if (!matched)
            say(command, "note: the rules' suppression {\"material\": \"" + s.material + "\", \"code\": \"" + s.code +
                             "\"} matches no material of this run");
    }
}

}  // namespace mf::cli
