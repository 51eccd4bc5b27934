// matforge ingest <input>... -o <out-dir> [--preset NAME|FILE] [--jobs N] [--fail-on ...]
#include <unistd.h>

#include <iostream>
#include <memory>

#include "command.hpp"
#include "options.hpp"
#include "process/ingest.hpp"
#include "process/validate_batch.hpp"

namespace mf::cli {
namespace {

struct IngestArgs {
    std::vector<std::string> inputs;
    std::string out_dir, preset = "gltf", fail_on = "error", normal, rules_file;
    int jobs = 0;
    bool quiet = false;
};

int run_ingest(const IngestArgs& a) {
    std::string error = output_overlaps_input(a.out_dir, {a.inputs.begin(), a.inputs.end()});
    if (!error.empty()) {
        std::cerr << "matforge ingest: " << error << "\n";
        return kExitUsage;
    }
    auto preset = load_preset(a.preset, error);
    if (!preset) {
        std::cerr << "matforge ingest: " << error << "\n";
        return kExitUsage;
    }
    auto rules = load_rule_config(*preset, a.rules_file, error);
    if (!rules) {
        std::cerr << "matforge ingest: " << error << "\n";
        return kExitUsage;
    }
    auto color = ColorContext::create(error);
    if (!color) {
        std::cerr << "matforge ingest: " << error << "\n";
        return kExitUsage;
    }
    IngestOptions opt;
    opt.out_dir = a.out_dir;
    opt.jobs = a.jobs;
    opt.rules = std::move(*rules);
    if (!a.normal.empty()) opt.normal_override = convention_from_name(a.normal);
    const bool tty = ::isatty(STDERR_FILENO) && !a.quiet;
    if (tty) {
        opt.progress = [](size_t done, size_t total, const std::string& name, const std::string& status) {
            std::cerr << "\r\033[K[" << done << "/" << total << "] " << name << " " << status << std::flush;
            if (done == total) std::cerr << "\n";
        };
    }
    Ingestor ingestor(std::move(*preset), color, opt);
    std::vector<std::filesystem::path> inputs(a.inputs.begin(), a.inputs.end());
    const IngestResult r = ingestor.run(inputs);
    if (!r.error.empty()) {
        std::cerr << "matforge ingest: " << r.error << "\n";
        return kExitFindings;
    }
    for (const auto& f : r.manifest["failures"])
        std::cerr << "matforge ingest: " << f["code"].get<std::string>() << ": " << f["message"].get<std::string>() << "\n";
    size_t counts[3] = {0, 0, 0};
    for (const auto& m : r.manifest["materials"])
        for (const auto& f : m["findings"])
            ++counts[static_cast<int>(severity_from_name(f["severity"].get<std::string>()).value_or(Severity::error))];
    if (!a.quiet)
        std::cerr << "matforge ingest: " << r.materials << " materials, " << r.failures << " failed; findings: "
                  << counts[2] << " error, " << counts[1] << " warning, " << counts[0] << " info; manifest: "
                  << (std::filesystem::path(a.out_dir) / "manifest.json").string() << "\n";
    return findings_exit(r.worst, a.fail_on, r.failures > 0);
}

const Register reg{{"ingest", 10,
                    [](CLI::App& sub) -> std::function<int()> {
                        auto a = std::make_shared<IngestArgs>();
                        sub.add_option("inputs", a->inputs, "material folders, .zip files, or folders of many (recursive)")
                            ->required();
                        sub.add_option("-o,--out", a->out_dir, "output folder (created; manifest.json goes here)")
                            ->required();
                        sub.add_option("--preset", a->preset, "shipped preset name (see 'matforge presets') or a JSON file")
                            ->capture_default_str();
                        sub.add_option("-j,--jobs", a->jobs, "sets processed in parallel (0 = all cores)")
                            ->check(CLI::Range(0, 1024))
                            ->capture_default_str();
                        sub.add_option("--normal-convention", a->normal,
                                       "override the preset's normal-map convention (gl = +Y, dx = -Y)")
                            ->check(CLI::IsMember({"gl", "dx"}));
                        sub.add_option("--rules", a->rules_file,
                                       "JSON rule configuration for the checks ingest runs (docs/rules.md)");
                        add_fail_on(sub, a->fail_on);
                        sub.add_flag("-q,--quiet", a->quiet, "no progress or summary on stderr");
                        return [a] { return run_ingest(*a); };
                    },
                    "convert material sets to engine-ready textures and a manifest.json"}};

}  // namespace
}  // namespace mf::cli
