#include <algorithm>
#include <iostream>
#include <map>

#include "color/color.hpp"
#include "command.hpp"
#include "core/allocator.hpp"
#include "core/files.hpp"
#include "core/text.hpp"
#include "core/version.hpp"
#include "image/image.hpp"
#include "render/render.hpp"
#include "sets/sets.hpp"
#include "texture/texture.hpp"

namespace mf::cli {
std::vector<Command>& registry() {
    static std::vector<Command> commands;
    return commands;
}

namespace {
// `matforge --version`: the version, the build (its build-id: what the ingest cache's records
// name, so a farm's nodes can be compared), then each library that decides output bytes or
// reads inputs, as loaded at run time (an upgraded Debian library without a rebuild shows here).
std::string version_text() {
    std::string s = std::string(mf::kGenerator) + "\n";
    std::string error;
    const auto build = mf::code_identity(error);
    s += "  build " + (build ? *build : "unknown (" + error + ")") + "\n";
    for (const std::string& lib :
         {mf::image_library_versions(), mf::color_library_version(), mf::texture::encoder_versions(),
          mf::archive_library_version(), mf::crypto_library_version(), mf::render::vulkan_header_version(),
          std::string("CLI11 " CLI11_VERSION)})
        s += "  " + lib + "\n";
    s.pop_back();  // CLI11 ends the text with its own newline
    return s;
}

// A parse error as every other message of matforge: "matforge <command>: <what>", with the
// nearest option or command when the word looks like a typo of one, and where to read more.
int usage_error(const CLI::App& app, const CLI::ParseError& e, int argc, char** argv) {
    const CLI::App* sub = nullptr;
    for (const CLI::App* s : app.get_subcommands()) sub = s;
    const std::string where = sub ? sub->get_name() : std::string();
    std::string hint;
    if (sub)
        for (int i = 1; i < argc && hint.empty(); ++i) {
            const std::string arg = argv[i];
            if (arg.rfind("--", 0) != 0) continue;
            const std::string name = arg.substr(0, arg.find('='));
            std::vector<std::string> options;
            for (const CLI::Option* o : sub->get_options())
                for (const std::string& l : o->get_lnames()) options.push_back("--" + l);
            if (std::find(options.begin(), options.end(), name) != options.end()) continue;
            if (const std::string near = nearest(name, options); !near.empty()) hint = "; did you mean " + near + "?";
        }
    say(where.empty() ? std::string_view("") : std::string_view(where),
        e.what() + hint + " (matforge " + where + (where.empty() ? "" : " ") + "--help lists them)");
    return static_cast<int>(ExitCode::usage);
}
}  // namespace
}  // namespace mf::cli

int main(int argc, char** argv) {
    mf::prefer_heap_reuse_for_large_images();  // first: before any thread or large block exists
    using namespace mf::cli;
    CLI::App app{"matforge — PBR material sets to engine-ready textures, CI checks and previews"};
    app.set_version_flag("--version", version_text, "print the version and the versions of the libraries in use");
    app.require_subcommand(1);
    auto commands = registry();
    std::sort(commands.begin(), commands.end(), [](const Command& a, const Command& b) { return a.order < b.order; });
    std::map<CLI::App*, std::function<ExitCode()>> runs;
    for (auto& c : commands) {
        CLI::App* sub = app.add_subcommand(c.name, c.description);
        runs[sub] = c.setup(*sub);
    }
    // A first word that is no command (`matforge injest`): say so, with the nearest command.
    if (argc > 1 && argv[1][0] != '-') {
        std::vector<std::string> names;
        names.reserve(commands.size());
        for (const auto& c : commands) names.push_back(c.name);
        if (std::find(names.begin(), names.end(), argv[1]) == names.end()) {
            const std::string near = mf::nearest(argv[1], names);
            say("", "'" + mf::terminal_safe(argv[1]) + "' is not a command" +
                        (near.empty() ? "" : "; did you mean '" + near + "'?") + " (matforge --help lists them)");
            return static_cast<int>(ExitCode::usage);
        }
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        // --help and --version are successes; every other parse error is a usage error.
        return usage_error(app, e, argc, argv);
    }
    for (auto& [sub, run] : runs)
        if (sub->parsed()) return static_cast<int>(run());
    return static_cast<int>(ExitCode::usage);
}
