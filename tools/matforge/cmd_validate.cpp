// matforge validate <input>... [--preset NAME|FILE] [--report text|json|junit|sarif|html]
//                   [--report-file F] [--rules FILE] [--fail-on ...] [--jobs N]
// Every report is written by lib/report from the run's manifest (no outputs): the same writers
// as ingest's --report and `matforge report`'s page.
#include <iostream>
#include <memory>

#include "command.hpp"
#include "core/files.hpp"
#include "options.hpp"
#include "process/validate_batch.hpp"
#include "report/formats.hpp"
#include "report/report.hpp"
#include "sets/sets.hpp"
#include "stop.hpp"

namespace mf::cli {
namespace {

struct ValidateArgs {
    std::vector<std::string> inputs;
    std::string preset = "gltf", report = "text", report_file, rules_file, fail_on = "error";
    int jobs = 0;
    bool verbose = false;
};

ExitCode run_validate(const ValidateArgs& a) {
    if (std::string why = no_usable_input({a.inputs.begin(), a.inputs.end()}); !why.empty())
        return fail("validate", why);
    std::string error;
    auto preset = load_preset(a.preset, error);
    if (!preset) return fail("validate", error);
    auto rules = load_rule_config(*preset, a.rules_file, error);
    if (!rules) return fail("validate", error);
    const std::vector<std::filesystem::path> inputs(a.inputs.begin(), a.inputs.end());
    const bool html = a.report == "html";
    if (html && a.report_file.empty()) return fail("validate", "--report html needs --report-file FOLDER");
    const Batch batch = Batch::find(inputs);
    if (!a.report_file.empty()) {  // checked before any map is read: the report never replaces an input
        const std::filesystem::path written = html ? std::filesystem::path(a.report_file) / "index.html"
                                                   : std::filesystem::path(a.report_file);
        std::string why = written_file_conflict(written, inputs, batch.sets);
        if (why.empty() && html) why = output_overlaps_input(a.report_file, inputs);
        if (!why.empty()) return fail("validate", "--report-file " + why);
    }
    ValidateBatchOptions opt;
    opt.jobs = a.jobs;
    opt.rules = std::move(*rules);
    install_stop_handlers();
    for (const std::string& n : batch.skipped) say("validate", "note: " + n);
    const manifest::Manifest report = validate_batch(batch, *preset, opt);
    if (stop_requested()) return interrupted("validate", "stopped before the end; no report is written");
    std::vector<std::string> names;
    for (const auto& m : report.materials) names.push_back(m.name);
    report_unmatched_suppressions("validate", opt.rules, names);
    const auto fail_on = fail_on_of(a.fail_on);
    const bool fails = validate::run_fails(validate::summarize(report), fail_on);
    if (html) {
        report::Options o;
        o.out = a.report_file;
        report::Result r;
        if (!report::write_report(o, report, {}, r, error)) return fail("validate", error);
        for (const std::string& p : r.problems) say("validate", "report: " + p);
        std::cerr << terminal_safe(report::write_terminal_summary(report, fail_on), true);
        return verdict_exit(fails);
    }
    const auto format = report::format_from_name(a.report).value_or(report::Format::text);
    // The text report on a terminal: its errors and warnings and the verdict (--verbose: all of
    // it). A report written to a file is whole, and the terminal still gets the summary on
    // stderr: a red CI job never has an empty log.
    const bool brief = format == report::Format::text && a.report_file.empty() && !a.verbose;
    std::string text = brief ? report::write_terminal_summary(report, fail_on)
                             : report::write_findings(report, format, fail_on);
    if (format == report::Format::text) text = terminal_safe(text, true);  // read in terminals
    if (a.report_file.empty()) {
        std::cout << text;
        if (!text.empty() && text.back() != '\n') std::cout << "\n";
    } else if (!write_file_atomic(a.report_file,
                                  std::span(reinterpret_cast<const unsigned char*>(text.data()), text.size()), error)) {
        return fail("validate", error);
    } else {
        std::cerr << terminal_safe(report::write_terminal_summary(report, fail_on), true);
    }
    return verdict_exit(fails);
}

const Register register_validate{
    {"validate", 20,
     [](CLI::App& sub) -> std::function<ExitCode()> {
         auto a = std::make_shared<ValidateArgs>();
         sub.add_option("inputs", a->inputs, "material folders, .zip files, or folders of many (recursive)")
             ->required();
         sub.add_option("--preset", a->preset, "preset whose needs (MISSING_MAP) and validate block apply")
             ->capture_default_str();
         sub.add_option("--report", a->report, "report format")
             ->check(CLI::IsMember({"text", "json", "junit", "sarif", "html"}))
             ->capture_default_str();
         sub.add_option("--report-file", a->report_file,
                        "write the report here instead of stdout (html: a folder, index.html in it)");
         sub.add_option("--rules", a->rules_file,
                        "JSON rule configuration: thresholds, severities, suppressions (docs/rules.md)");
         sub.add_option("-j,--jobs", a->jobs, "sets validated in parallel (0 = all cores)")
             ->check(CLI::Range(0, 1024))
             ->capture_default_str();
         add_fail_on(sub, a->fail_on);
         sub.add_flag("-v,--verbose", a->verbose,
                      "print the whole text report (every material's maps and info findings), not only its "
                      "errors, warnings and verdict");
         return [a] { return run_validate(*a); };
     },
     "check material sets (PBR plausibility, channels, normal convention) for CI"}};

}  // namespace
}  // namespace mf::cli
