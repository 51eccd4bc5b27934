#include <algorithm>
#include <iostream>
#include <map>

#include "command.hpp"
#include "core/allocator.hpp"
#include "core/version.hpp"

namespace mf::cli {
std::vector<Command>& registry() {
    static std::vector<Command> commands;
    return commands;
}
}  // namespace mf::cli

int main(int argc, char** argv) {
    mf::prefer_heap_reuse_for_large_images();  // first: before any thread or large block exists
    using namespace mf::cli;
    CLI::App app{"matforge — PBR material sets to engine-ready textures, CI checks and previews"};
    app.set_version_flag("--version", std::string(mf::kGenerator));
    app.require_subcommand(1);
    auto commands = registry();
    std::sort(commands.begin(), commands.end(), [](const Command& a, const Command& b) { return a.order < b.order; });
    std::map<CLI::App*, std::function<ExitCode()>> runs;
    for (auto& c : commands) {
        CLI::App* sub = app.add_subcommand(c.name, c.description);
        runs[sub] = c.setup(*sub);
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int rc = app.exit(e);
        // --help and --version are successes; every other parse error is a usage error.
        return static_cast<int>(rc == 0 ? ExitCode::ok : ExitCode::usage);
    }
    for (auto& [sub, run] : runs)
        if (sub->parsed()) return static_cast<int>(run());
    return static_cast<int>(ExitCode::usage);
}
