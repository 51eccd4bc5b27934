// matforge ingest <input>... -o <out-dir> [--preset NAME|FILE[,...]] [--tiers N,N...] [--jobs N]
//                 [--fail-on ...] [--report text|json|junit|sarif|html [--report-file F]]
// The report is written from the manifest the run wrote, by validate's writers (lib/report).
#include <unistd.h>

#include <cstdlib>
#include <iostream>
#include <map>
#include <memory>
#include <set>

#include "command.hpp"
#include "core/files.hpp"
#include "options.hpp"
#include "process/ingest.hpp"
#include "process/validate_batch.hpp"
#include "process/work.hpp"
#include "report/formats.hpp"
#include "report/report.hpp"
#include "sets/sets.hpp"
#include "stop.hpp"
#include "store/cache.hpp"
#include "summary.hpp"

namespace mf::cli {
namespace {

struct IngestArgs {
    std::vector<std::string> inputs;
    std::string out_dir, preset = "gltf", fail_on = "error", normal, rules_file, shard, cache, report, report_file;
    std::string tiers;  // --tiers 512,1024: given when `tiers_given` (an empty value is an error, not "none")
    int jobs = 0;
    bool quiet = false, force = false, replace = false, no_cache = false, tiers_given = false;
};

// --report: the manifest just written, read back, through the writers validate uses; the
// sources as paths from here (the manifest keeps them relative to its folder). Empty or why not.
std::string write_ingest_report(const IngestArgs& a, const std::filesystem::path& manifest_file) {
    std::string error;
    if (a.report == "html") {
        report::Options o;
        o.manifest = manifest_file;
        o.out = a.report_file;
        report::Result r;
        if (!report::write_report(o, r, error)) return error;
        for (const std::string& p : r.problems) say("ingest", "report: " + p);
        return {};
    }
    auto m = manifest::read_manifest(manifest_file.string(), error);
    if (!m) return error;
    report::rebase_sources(*m, manifest_file.parent_path());
    const auto format = report::format_from_name(a.report).value_or(report::Format::text);
    std::string text = report::write_findings(*m, format, fail_on_of(a.fail_on));
    if (format == report::Format::text) text = terminal_safe(text, true);
    if (a.report_file.empty()) {
        std::cout << text;
        if (!text.empty() && text.back() != '\n') std::cout << "\n";
        return {};
    }
    if (!write_file_atomic(a.report_file, std::span(reinterpret_cast<const unsigned char*>(text.data()), text.size()),
                           error))
        return error;
    return {};
}

// The run's notes, each once; "removed <file>: <why>" lines of one reason beyond a few are
// counted, not listed (a preset switch removed 200 files in 200 lines, which hid the rest).
void say_notes(const std::string& command, const std::vector<std::string>& notes) {
    constexpr size_t kListed = 3;
    std::map<std::string, size_t> removed;  // why -> how many
    for (const auto& n : notes) {
        const size_t colon = n.find(": ");
        if (n.rfind("removed ", 0) == 0 && colon != std::string::npos && ++removed[n.substr(colon + 2)] > kListed)
            continue;
        say(command, "note: " + n);
    }
    for (const auto& [why, count] : removed)
        if (count > kListed)
            say(command,
                "note: removed " + std::to_string(count - kListed) + " more files for the same reason (" + why + ")");
}

// What one preset's run tells its user, and its exit code. `command`: "ingest", or with several
// runs "ingest [FOLDER]", the run's folder under the output folder (NAME, TIER, NAME/TIER).
ExitCode report_run(const IngestArgs& a, const IngestOptions& opt, const IngestResult& r, const std::string& command) {
    const std::filesystem::path manifest = opt.out_dir / opt.manifest_name;
    if (r.interrupted)
        return interrupted(command, "stopped before the end; " + manifest.string() +
                                        " is not written until a run completes (run the command again to finish)");
    if (!r.error.empty()) return fail(command, r.error, r.usage_error ? ExitCode::usage : ExitCode::findings);
    if (!a.quiet) say_notes(command, r.notes);
    for (const auto& p : r.cache_problems) say(command, "warning: cache: " + p);
    if (!a.quiet && opt.cache_dir && r.cache_hits + r.cache_misses > 0)
        say(command, "cache: " + std::to_string(r.cache_hits) + " sets restored, " + std::to_string(r.cache_misses) +
                         " computed (" + opt.cache_dir->string() + ")");
    std::vector<std::string> names;
    for (const auto& m : r.materials) names.push_back(m.name);
    report_unmatched_suppressions(command, opt.rules, names);
    for (const auto& f : r.manifest.failures) say(command, f.code + ": " + f.message);
    if (!a.quiet) {
        const validate::Summary counts = summarize(r);
        say(command, std::to_string(r.materials.size()) + " materials, " + std::to_string(r.manifest.failures.size()) +
                         " failed; findings: " + std::to_string(counts.error) + " error, " +
                         std::to_string(counts.warning) + " warning, " + std::to_string(counts.info) +
                         " info; manifest: " + manifest.string());
        print_attention(command, r);
    }
    if (!a.report.empty())
        if (std::string why = write_ingest_report(a, manifest); !why.empty()) return fail(command, why);
    return verdict_exit(validate::run_fails(summarize(r), fail_on_of(a.fail_on)));
}

ExitCode run_ingest(const IngestArgs& a) {
    // Nothing to read (a typo'd folder): stop before anything is created.
    if (std::string why = no_usable_input({a.inputs.begin(), a.inputs.end()}); !why.empty()) return fail("ingest", why);
    std::string error = output_overlaps_input(a.out_dir, {a.inputs.begin(), a.inputs.end()});
    if (!error.empty()) return fail("ingest", error);
    if (!a.report_file.empty() && a.report.empty()) return fail("ingest", "--report-file needs --report FORMAT");
    if (a.report == "html" && a.report_file.empty()) return fail("ingest", "--report html needs --report-file FOLDER");
    // --preset a,b: one output folder a preset, <out>/<its name>, each what a run of that preset
    // alone into that folder writes (process/ingest.hpp's run_together).
    std::vector<std::string> names;
    for (size_t at = 0; at <= a.preset.size();) {
        const size_t comma = std::min(a.preset.find(',', at), a.preset.size());
        names.push_back(a.preset.substr(at, comma - at));
        at = comma + 1;
    }
    const bool several = names.size() > 1;
    if (several && !a.report.empty())
        return fail("ingest", "--report takes one preset's run; with several, run `matforge validate` or `matforge "
                              "report` on each preset's folder");
    // --tiers 512,1024: each preset once per tier, with that max_size, into <its folder>/<tier>;
    // it replaces the presets' own max_size (a number, or a list of tiers).
    std::optional<std::vector<int>> tiers;
    if (a.tiers_given && !(tiers = parse_tiers(a.tiers, error))) return fail("ingest", error);
    auto color = ColorContext::create(error);
    if (!color) return fail("ingest", error);
    std::vector<std::unique_ptr<Ingestor>> ingestors;
    std::vector<IngestOptions> options;
    std::set<std::string> folders;
    std::vector<std::string> labels;  // each run says its own summary
    // One run of the pass: `preset` (a tier's, with its max_size) into `folder`, labelled `label`.
    // Empty, or why the run cannot be.
    auto add_run = [&](Preset preset, const rules::RuleConfig& rules, const std::filesystem::path& folder,
                       const std::string& label) -> std::string {
        IngestOptions opt;
        opt.out_dir = folder;
        opt.jobs = a.jobs;
        opt.rules = rules;
        opt.force = a.force;
        opt.replace = a.replace;
        if (!a.no_cache) opt.cache_dir = cache_folder(a.cache);
        if (opt.cache_dir) {
            const std::vector<std::filesystem::path> inputs(a.inputs.begin(), a.inputs.end());
            if (std::string why = cache_overlaps(*opt.cache_dir, opt.out_dir, inputs); !why.empty()) return why;
            // A folder the user named must be a cache (or new); the default one, if foreign, is
            // left alone with a warning and the run goes on without it (process/ingest.cpp).
            const bool named = !a.cache.empty() || std::getenv("MATFORGE_CACHE") != nullptr;
            if (std::string why = Cache::unusable(*opt.cache_dir); named && !why.empty()) return why;
        }
        if (!a.normal.empty()) opt.normal_override = convention_from_name(a.normal);
        if (!a.shard.empty()) {
            opt.shard = parse_shard(a.shard);
            if (!opt.shard) return "--shard must be I/N with 0 <= I < N, not \"" + a.shard + "\"";
            opt.manifest_name = "manifest.shard-" + std::to_string(opt.shard->first) + "-of-" +
                                std::to_string(opt.shard->second) + ".json";
        }
        const bool tty = ::isatty(STDERR_FILENO) && !a.quiet;
        if (tty && ingestors.empty()) {  // one progress line: the first run's (the others follow it set by set)
            opt.progress = [](size_t done, size_t total, const std::string& set, const MaterialResult& r) {
                std::cerr << "\r\033[K[" << done << "/" << total << "] " << terminal_safe(set) << " " << set_status(r)
                          << std::flush;
                if (done == total) std::cerr << "\n";
            };
        }
        options.push_back(opt);
        labels.push_back(label);
        ingestors.push_back(std::make_unique<Ingestor>(std::move(preset), color, std::move(opt)));
        return {};
    };
    for (const std::string& name : names) {
        if (name.empty()) return fail("ingest", "--preset \"" + a.preset + "\" names an empty preset");
        auto preset = load_preset(name, error);
        if (!preset) return fail("ingest", error);
        auto rules = load_rule_config(*preset, a.rules_file, error);
        if (!rules) return fail("ingest", error);
        const auto folder = preset_output_folder(a.out_dir, preset->name, names.size(), folders, error);
        if (!folder) return fail("ingest", name + ": " + error);
        const std::vector<int> preset_tiers = tiers ? *tiers : preset->tiers;
        const std::string prefix = several ? preset->name + "/" : "";
        std::string why;
        if (preset_tiers.empty()) {
            const std::string label = several ? "ingest [" + preset->name + "]" : "ingest";
            why = add_run(std::move(*preset), *rules, *folder, label);
        }
        for (size_t t = 0; t < preset_tiers.size() && why.empty(); ++t) {
            const std::string tier = std::to_string(preset_tiers[t]);
            why = add_run(with_max_size(*preset, preset_tiers[t]), *rules, *folder / tier,
                          "ingest [" + prefix + tier + "]");
        }
        if (!why.empty()) return fail("ingest", why);
    }
    if (ingestors.size() > 1 && !a.report.empty())  // one preset, several tiers
        return fail("ingest", "--report takes one run's findings; with several tiers, run `matforge validate` or "
                              "`matforge report` on each tier's folder");
    std::vector<const Ingestor*> all;
    all.reserve(ingestors.size());
    for (const auto& i : ingestors) all.push_back(i.get());
    // The sets, found once for every preset, never inside one of the run's output folders.
    const std::vector<std::filesystem::path> inputs(a.inputs.begin(), a.inputs.end());
    std::vector<std::filesystem::path> outputs;
    outputs.reserve(options.size());
    for (const IngestOptions& o : options) outputs.push_back(o.out_dir);
    Batch batch = Batch::find(inputs, outputs);
    if (!a.report_file.empty()) {  // checked before any map is read: the report never replaces an input
        const bool html = a.report == "html";
        const std::filesystem::path written = html ? std::filesystem::path(a.report_file) / "index.html"
                                                   : std::filesystem::path(a.report_file);
        std::string why = written_file_conflict(written, inputs, batch.sets);
        if (why.empty() && html) why = output_overlaps_input(a.report_file, inputs);
        if (!why.empty()) return fail("ingest", "--report-file " + why);
    }
    install_stop_handlers();
    const std::vector<IngestResult> results = Ingestor::run_together(all, std::move(batch));
    ExitCode worst = ExitCode::ok;
    for (size_t i = 0; i < results.size(); ++i) {
        const ExitCode code = report_run(a, options[i], results[i], labels[i]);
        if (code == ExitCode::interrupted_int || code == ExitCode::interrupted_term) return code;
        if (static_cast<int>(code) > static_cast<int>(worst)) worst = code;
    }
    return worst;
}

const Register register_ingest{
    {"ingest", 10,
     [](CLI::App& sub) -> std::function<ExitCode()> {
         auto a = std::make_shared<IngestArgs>();
         sub.add_option("inputs", a->inputs, "material folders, .zip files, or folders of many (recursive)")
             ->required();
         sub.add_option("-o,--out", a->out_dir, "output folder (created; manifest.json goes here)")->required();
         sub.add_option("--preset", a->preset,
                        "shipped preset name (see 'matforge presets') or a JSON file; several, comma-separated "
                        "(gltf,unity-hdrp), write each into <out>/<its name> in one pass: each set decoded once")
             ->capture_default_str();
         const std::string tiers_help =
             "resolution tiers: largest output sides in pixels (1-65536), comma-separated (512,1024,2048); each "
             "tier written into <out>/<tier> (<out>/<preset>/<tier> with several presets), what the preset with "
             "that max_size writes there alone, in one pass: each map decoded once for every tier; never "
             "upsampled (smaller sets keep their size). Replaces the presets' max_size (a preset's list "
             "\"max_size\": [512, 1024] gives its tiers without this option)";
         CLI::Option* tiers = sub.add_option("--tiers", a->tiers, tiers_help)->type_name("N,N...");
         sub.add_option("-j,--jobs", a->jobs, "sets processed in parallel (0 = all cores)")
             ->check(CLI::Range(0, 1024))
             ->capture_default_str();
         sub.add_option("--normal-convention", a->normal,
                        "override the preset's normal-map convention (gl = +Y, dx = -Y)")
             ->check(CLI::IsMember({"gl", "dx"}));
         sub.add_option("--rules", a->rules_file, "JSON rule configuration for the checks ingest runs (docs/rules.md)");
         sub.add_option("--shard", a->shard,
                        "I/N: process only shard I of N (sets assigned by size, as `matforge plan --shards N` "
                        "lists them); writes manifest.shard-I-of-N.json for `matforge merge`");
         add_fail_on(sub, a->fail_on);
         sub.add_option("--report", a->report,
                        "also write the run's findings as validate does (from the manifest written): text, json, "
                        "junit, sarif, or html (a `matforge report` page)")
             ->check(CLI::IsMember({"text", "json", "junit", "sarif", "html"}));
         sub.add_option("--report-file", a->report_file,
                        "write the --report here instead of stdout (html: a folder, index.html in it)");
         sub.add_flag("-q,--quiet", a->quiet, "no progress or summary on stderr");
         auto* cache = sub.add_option("--cache", a->cache,
                                      "result cache folder (default $MATFORGE_CACHE, else $XDG_CACHE_HOME/matforge or "
                                      "~/.cache/matforge): unchanged sets are restored, not recomputed");
         sub.add_flag("--no-cache", a->no_cache, "compute every set; read and write no cache")->excludes(cache);
         sub.add_flag("--force", a->force,
                      "replace a manifest.json matforge did not write, and files in the way of outputs "
                      "that no earlier run wrote (refused without it)");
         sub.add_flag("--replace", a->replace,
                      "write into a folder that holds another preset's outputs, replacing them (refused "
                      "without it)");
         return [a, tiers] {
             a->tiers_given = tiers->count() > 0;
             return run_ingest(*a);
         };
     },
     "convert material sets to engine-ready textures and a manifest.json"}};

}  // namespace
}  // namespace mf::cli
