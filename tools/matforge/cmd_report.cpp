// matforge report <manifest.json> -o <dir> [--previews DIR] [--compare MANIFEST2]
//   [--compare-previews DIR] [--thumb-size N] [--page-size N] [--jobs N] [--no-sources]
//   [--allow-outside] [--viewer] [--quiet]
// One static HTML page (dir/index.html, pictures in dir/<material>/, rules in dir/rules.html)
// that opens from disk with no network.
#include <chrono>
#include <cstdio>
#include <memory>

#include "command.hpp"
#include "report/report.hpp"
#include "stop.hpp"

namespace mf::cli {
namespace {

struct ReportArgs {
    std::string manifest, out, previews, compare, compare_previews;
    int thumb_size = 256, page_size = 50, jobs = 0;
    bool no_sources = false, allow_outside = false, viewer = false, quiet = false;
};

ExitCode run_report(const ReportArgs& a) {
    report::Options o;
    o.manifest = a.manifest;
    o.out = a.out;
    if (!a.previews.empty()) o.previews = a.previews;
    if (!a.compare.empty()) o.compare = a.compare;
    if (!a.compare_previews.empty()) {
        if (a.compare.empty()) return fail("report", "--compare-previews needs --compare MANIFEST");
        o.compare_previews = a.compare_previews;
    }
    for (const std::string* dir : {&a.previews, &a.compare_previews}) {
        std::error_code ec;
        if (!dir->empty() && !std::filesystem::is_directory(*dir, ec))
            return fail("report", *dir + ": not a folder (give the -o folder of `matforge preview`)");
    }
    o.thumb_size = a.thumb_size;
    o.page_size = a.page_size;
    o.jobs = a.jobs;
    o.sources = !a.no_sources;
    o.allow_outside = a.allow_outside;
    o.viewer = a.viewer;
    const auto start = std::chrono::steady_clock::now();
    report::Result r;
    std::string error;
    install_stop_handlers();
    const bool written = report::write_report(o, r, error);
    if (stop_requested()) return interrupted("report", "stopped before the end; no index.html written");
    if (!written) {
        // An unreadable manifest is a usage error (as for preview); a page that cannot be written is 1.
        const bool written_part = !r.index.empty();
        return fail("report", error, written_part ? ExitCode::findings : ExitCode::usage);
    }
    for (const std::string& p : r.problems) say("report", p);
    if (!a.quiet) {
        const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        char t[32];
        std::snprintf(t, sizeof t, "%.2f s", s);
        say("report", std::to_string(r.materials) + " materials, " + std::to_string(r.findings) + " findings, " +
                          std::to_string(r.images) + " pictures in " + t + "; " + r.index.string());
    }
    return r.problems.empty() ? ExitCode::ok : ExitCode::findings;
}

const Register register_report{
    {"report", 32,
     [](CLI::App& sub) -> std::function<ExitCode()> {
         auto a = std::make_shared<ReportArgs>();
         sub.add_option("manifest", a->manifest, "manifest.json written by `matforge ingest`")->required();
         sub.add_option("-o,--out", a->out, "the report's folder: index.html, rules.html and <material>/*.png")
             ->required();
         sub.add_option(
             "--previews", a->previews,
             "the -o folder of `matforge preview` (<material>.png): the contact sheet and each card's preview");
         sub.add_option(
             "--compare", a->compare,
             "the manifest of another preset's ingest of the same sets: its outputs beside this one's (before/after)");
         sub.add_option("--compare-previews", a->compare_previews, "the previews of the --compare manifest");
         sub.add_option("--thumb-size", a->thumb_size, "longest side of every picture, pixels, 16..2048 (default 256)")
             ->check(CLI::Range(16, 2048));
         sub.add_option("--page-size", a->page_size, "cards per page in the browser, 1..100000 (default 50)")
             ->check(CLI::Range(1, 100000));
         sub.add_option("-j,--jobs", a->jobs, "materials in parallel, 0..1024; 0 = one per hardware thread (default 0)")
             ->check(CLI::Range(0, 1024));
         sub.add_flag("--no-sources", a->no_sources, "no thumbnails of the source maps (faster on large libraries)");
         sub.add_flag("--allow-outside", a->allow_outside,
                      "read manifest outputs that lie outside the manifest's folder");
         sub.add_flag("--viewer", a->viewer,
                      "on each card an interactive view: the material turned in WebGL2 (sphere, plane, shaderball) "
                      "under the look-dev lighting of `matforge preview`, drawn by its own shaders; maps at most "
                      "512 px a side, loaded when a view is opened; needs a Vulkan device (a GPU, else lavapipe)");
         sub.add_flag("-q,--quiet", a->quiet, "no summary line on stderr");
         return [a] { return run_report(*a); };
     },
     "write a static HTML report of a manifest: previews, sources, outputs, findings, range overlays"}};

}  // namespace
}  // namespace mf::cli
