// `matforge report`: one static HTML page over a manifest (index.html, with its pictures beside
// it), opened from disk or from a CI artifact with no network: a contact sheet, and per material
// a card with its sources and their roles, the packed outputs with their channel layout, the
// findings (linked to rules.html, docs/rules.md rendered beside the page), the normal-convention
// verdict with its evidence, false-colour overlays of the albedo's range and of non-binary
// metalness, and before/after views (source map vs output; one preset's preview vs another's).
//
// Conventions of this module (decided once here):
//  - layout of the output folder: index.html, rules.html, and <stem>/*.png per material
//    (material_stem(): the manifest's name made one safe path component, unique without case);
//  - the page is deterministic (no timestamp, no absolute path the user did not give): the same
//    manifest and images give the same bytes, and files whose bytes would not change are not
//    rewritten (core/files write_file_atomic);
//  - paging: every card is in the HTML (a browser without JavaScript shows them all, images
//    loading lazily); the inline script shows `page_size` cards at a time;
//  - a picture that cannot be read or written is a note in the card and in Result::problems,
//    never a stop: the page is always written.
#pragma once
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "manifest/manifest.hpp"
#include "report/images.hpp"

namespace mf::report {

struct Options {
    std::filesystem::path manifest;                         // manifest.json written by `matforge ingest`
    std::filesystem::path out;                              // the report's folder (index.html at its top)
    std::optional<std::filesystem::path> previews;          // `matforge preview` output: <name>.png
    std::optional<std::filesystem::path> compare;           // another preset's manifest of the same sets
    std::optional<std::filesystem::path> compare_previews;  // its previews
    int thumb_size = 256;                                   // longest side of every picture written, pixels
    int page_size = 50;                                     // cards per page (the script's paging)
    int jobs = 0;                                           // materials in parallel; 0 = one per hardware thread
    bool sources = true;         // thumbnails of the source maps (the "before" of before/after)
    bool allow_outside = false;  // read outputs that lie outside the manifest's folder
    // Each card's interactive view (report/viewer.hpp): the material turned in WebGL2 under the
    // look-dev lighting of `matforge preview`; needs a Vulkan device (a GPU, else lavapipe).
    bool viewer = false;
    // The thresholds the overlays judge by; nullopt: the manifest's (the run's rules), so the
    // page's shares are its findings'.
    std::optional<rules::Thresholds> thresholds;
    // Decoded pixels in flight across the materials running at once, as ingest's
    // (process/ingest.hpp): a material waits for its share, and one larger than the whole runs alone.
    uint64_t memory_budget = uint64_t{1} << 30;
};

struct Result {
    size_t materials = 0, findings = 0, images = 0;  // images written (or already identical)
    std::vector<std::string> problems;               // "material: what could not be shown"
    std::filesystem::path index;                     // out/index.html
};

// Writes the report. False + `error` when the manifest (or --compare's) cannot be read or
// index.html cannot be written; problems with single pictures go to Result::problems.
bool write_report(const Options& options, Result& result, std::string& error);
// The same page over a manifest that is no file (`matforge validate`'s: no outputs, so the
// overlays judge the source maps): its sources are relative to `sources_dir`; options.manifest
// is ignored (the page is titled "matforge validate").
bool write_report(const Options& options, const manifest::Manifest& m, const std::filesystem::path& sources_dir,
                  Result& result, std::string& error);

// The folder name of each material in order: its name with characters outside [A-Za-z0-9._-]
// as '_', no leading '.', at most 96 bytes, unique compared without case and never "index.html"
// or "rules.html" (then "_2", "_3" … as ingest names sets).
std::vector<std::string> material_stems(const std::vector<std::string>& names);

// The file `matforge preview` wrote for material `name` in `dir` (as its -o documents: '/', '\',
// ':', '*', '?', '"', '<', '>', '|' become '_'), or nullopt when there is none.
std::optional<std::filesystem::path> preview_file(const std::filesystem::path& dir, const std::string& name);

// rules.html: docs/rules.md (embedded at build time) as HTML, every rule's table row with the
// id its catalog anchor names, and a section listing the other codes seen in `codes` (those of
// other stages, which rules.md names in prose) so every finding's link has a target.
std::string rules_page(const std::set<std::string>& codes);
// The link of a finding code into rules.html ("rules.html#anchor").
std::string rule_link(const std::string& code);

}  // namespace mf::report
