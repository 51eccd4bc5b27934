#include <algorithm>
#include <iostream>
#include <map>

#include "command.hpp"
#include "core/allocator.hpp"

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
    app.set_version_flag("--version", "matforge 0.1.0");
    app.require_subcommand(1);
    auto commands = registry();
    std::sort(commands.begin(), commands.end(),
              [](const Command& a, const Command& b) { return a.order < b.order; });
    std::map<CLI::App*, std::function<int()>> runs;
    for (auto& c : commands) {
        CLI::App* sub = app.add_subcommand(c.name, c.description);
        runs[sub] = c.setup(*sub);
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int rc = app.exit(e);
        // --help and --version are successes; every other parse error is a usage error.
        return rc == 0 ? kExitOk : kExitUsage;
    }
    for (auto& [sub, run] : runs)
        if (sub->parsed()) return run();
    return kExitUsage;
}
