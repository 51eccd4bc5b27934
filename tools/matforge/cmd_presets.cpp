// matforge presets [list | show NAME|FILE]
#include <iostream>
#include <memory>

#include "command.hpp"
#include "preset/preset.hpp"

namespace mf::cli {
namespace {

struct PresetsArgs {
    std::string action = "list", name;
};

ExitCode run_presets(const PresetsArgs& a) {
    std::string error;
    if (a.action == "list") {
        for (const auto& n : shipped_presets()) {
            auto p = load_preset(n, error);
            std::cout << n << "\t" << (p ? p->engine_convention : error) << "\n";
        }
        return ExitCode::ok;
    }
    if (a.name.empty()) {
        return fail("presets", "show: name a preset");
    }
    auto p = load_preset(a.name, error);
    if (!p) {
        return fail("presets", error);
    }
    std::cout << p->source_json.dump(2) << "\n";
    return ExitCode::ok;
}

const Register register_presets{{"presets", 40,
                                 [](CLI::App& sub) -> std::function<ExitCode()> {
                                     auto a = std::make_shared<PresetsArgs>();
                                     sub.add_option("action", a->action, "list | show")
                                         ->check(CLI::IsMember({"list", "show"}))
                                         ->capture_default_str();
                                     sub.add_option("name", a->name, "preset name or JSON file (for show)");
                                     return [a] { return run_presets(*a); };
                                 },
                                 "list the shipped presets or print one"}};

}  // namespace
}  // namespace mf::cli
