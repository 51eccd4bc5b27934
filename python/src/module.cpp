// matforge._core: the library's commands for Python (python/matforge/__init__.py wraps them in
// typed objects). Each function does what its command in tools/matforge/cmd_*.cpp does before
// and around the library call (the same checks, the same library entry points), and returns
// what the command would write (the manifest, the plan) as Python values: the library's own
// to_json, so a figure is an int or a float exactly as the JSON reports hold it.
#include <pybind11/functional.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "color/color.hpp"
#include "core/files.hpp"
#include "core/json.hpp"
#include "core/version.hpp"
#include "image/image.hpp"
#include "manifest/manifest.hpp"
#include "manifest/spool.hpp"
#include "options.hpp"  // tools/matforge: the cache folder's rule and --fail-on, as the CLI reads them
#include "plan/plan.hpp"
#include "process/ingest.hpp"
#include "process/material_file.hpp"
#include "process/validate_batch.hpp"
#include "process/work.hpp"
#include "run.hpp"
#include "sets/sets.hpp"
#include "store/cache.hpp"
#include "texture/texture.hpp"
#include "validate/verdict.hpp"

namespace mfpy {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// JSON as Python values: objects as dicts (keys in the JSON's order), integers as int, other
// numbers as float.
py::object to_py(const json& j) {
    switch (j.type()) {
        case json::value_t::null: return py::none();
        case json::value_t::boolean: return py::bool_(j.get<bool>());
        case json::value_t::number_integer: return py::int_(j.get<int64_t>());
        case json::value_t::number_unsigned: return py::int_(j.get<uint64_t>());
        case json::value_t::number_float: return py::float_(j.get<double>());
        case json::value_t::string: return py::str(j.get_ref<const std::string&>());
        case json::value_t::array: {
            py::list l;
            for (const json& e : j) l.append(to_py(e));
            return l;
        }
        case json::value_t::object: {
            py::dict d;
            for (const auto& [k, v] : j.items()) d[py::str(k)] = to_py(v);
            return d;
        }
        default: return py::none();  // binary and discarded values: never in our JSON
    }
}

std::vector<fs::path> paths_of(const std::vector<std::string>& inputs) { return {inputs.begin(), inputs.end()}; }

// Nothing to read (a typo'd folder): the error every command gives before it creates anything.
void require_input(const std::vector<std::string>& inputs) {
    if (inputs.empty()) throw Failure("UsageError", "usage", "no input given");
    if (std::string why = mf::no_usable_input(paths_of(inputs)); !why.empty())
        throw Failure("InputError", std::string(mf::code::input_not_found), why);
}

mf::Preset preset_of(const std::string& name) {
    std::string error;
    auto preset = mf::load_preset(name, error);
    if (!preset) throw Failure("UsageError", "usage", error);
    return std::move(*preset);
}

// The preset's "validate" block, then a rules file or a rules object (JSON text) over it.
mf::rules::RuleConfig rules_of(const mf::Preset& preset, const std::string& file, const std::string& text) {
    std::string error;
    auto rules = mf::load_rule_config(preset, file, error);
    if (!rules) throw Failure("UsageError", "usage", error);
    if (text.empty()) return std::move(*rules);
    const json j = json::parse(text, nullptr, false);
    if (j.is_discarded()) throw Failure("UsageError", "usage", "rules: not JSON");
    auto layered = mf::rules::RuleConfig::from_json(j, error, *rules);
    if (!layered) throw Failure("UsageError", "usage", "rules: " + error);
    return std::move(*layered);
}

std::shared_ptr<const mf::ColorContext> color_context() {
    std::string error;
    auto color = mf::ColorContext::create(error);
    if (!color) throw Failure("UsageError", "usage", error);
    return color;
}

json candidate_json(const mf::Candidate& c) {
    json j = {{"file", c.file},
              {"family", c.match.family},
              {"rule", c.match.rule},
              {"sidecar", c.match.sidecar},
              {"normal_convention", mf::convention_name(c.match.normal)},
              {"opacity_in_alpha", c.match.opacity_in_alpha},
              {"width", c.header.width},
              {"height", c.header.height},
              {"channels", c.header.channels},
              {"bit_depth", c.header.bit_depth},
              {"is_float", c.header.is_float}};
    json unused = json::array();
    for (const mf::Role r : c.match.unused) unused.push_back(mf::role_name(r));
    j["unused"] = std::move(unused);
    return j;
}

// `matforge.discover`: every set found under the inputs, each file's role as discovery decides
// it (plan/plan.hpp discover_roles: names, sidecars, headers), the findings it raises with the
// rules config applied as validate applies it.
py::object discover(const std::vector<std::string>& inputs, const std::string& preset_name,
                    const std::string& rules_file, const std::string& rules_text) {
    require_input(inputs);
    const mf::Preset preset = preset_of(preset_name);
    const mf::rules::RuleConfig rules = rules_of(preset, rules_file, rules_text);
    json out = {{"sets", json::array()}, {"failures", json::array()}, {"skipped", json::array()}};
    Watch watch(py::none(), nullptr);
    run_watched(watch, [&] {
        const mf::Batch batch = mf::Batch::find(paths_of(inputs));
        for (const mf::MaterialSource& src : batch.sets) {
            if (mf::stop_requested()) return;
            const mf::SetDiscovery d = mf::discover_roles(src, preset, &rules);
            json maps = json::array();
            for (const mf::RoleChoice& c : d.choices) {
                json m = candidate_json(c.chosen);
                m["role"] = mf::role_name(c.role);
                json rejected = json::array();
                for (const mf::Candidate& r : c.rejected) rejected.push_back(candidate_json(r));
                m["rejected"] = std::move(rejected);
                maps.push_back(std::move(m));
            }
            json findings = json::array();
            for (const mf::Finding& f : mf::reported_findings(d.findings, src.name, rules))
                findings.push_back(mf::to_json(f));
            out["sets"].push_back({{"name", src.name},
                                   {"source", src.display},
                                   {"root", src.root.string()},
                                   {"archive", src.is_zip ? json(src.root.string()) : json()},
                                   {"folder", src.zip_folder},
                                   {"files", src.files},
                                   {"convention", d.convention},
                                   {"maps", std::move(maps)},
                                   {"findings", std::move(findings)}});
        }
        for (const mf::InputFailure& f : batch.failures) out["failures"].push_back(mf::to_json(f));
        out["skipped"] = batch.skipped;
    });
    watch.raise_if_stopped(true);
    return to_py(out);
}

// `matforge.validate`: `matforge validate`'s run (process/validate_batch.hpp), its report as the
// manifest without outputs that every report format is written from.
py::object validate(const std::vector<std::string>& inputs, const std::string& preset_name,
                    const std::string& rules_file, const std::string& rules_text, int jobs, py::object progress,
                    std::shared_ptr<Cancel> cancel) {
    require_input(inputs);
    const mf::Preset preset = preset_of(preset_name);
    mf::ValidateBatchOptions opt;
    opt.jobs = jobs;
    opt.rules = rules_of(preset, rules_file, rules_text);
    Watch watch(std::move(progress), std::move(cancel));
    opt.progress = [&watch](size_t done, size_t total, const std::string& name) { watch.report(done, total, name); };
    mf::manifest::Manifest report;
    std::vector<std::string> skipped;
    run_watched(watch, [&] {
        const mf::Batch batch = mf::Batch::find(paths_of(inputs));
        skipped = batch.skipped;
        report = mf::validate_batch(batch, preset, opt);
    });
    watch.raise_if_stopped(true);  // `matforge validate` writes no report then, and neither do we
    py::object result = to_py(mf::manifest::to_json(report));
    result["skipped"] = skipped;
    return result;
}

// One run of an ingest pass: what it wrote and what it said.
struct RunOutcome {
    std::string folder;  // relative to the output folder: "" for one run, else preset, tier, preset/tier
    fs::path manifest;
    mf::IngestResult result;
};

// `matforge.ingest`: `matforge ingest`'s run (tools/matforge/cmd_ingest.cpp run_ingest): the
// same checks, then Ingestor::run_together over every preset and tier. `cache`: the folder, or
// "" for none (the caller resolves the default through default_cache()).
py::object ingest(const std::vector<std::string>& inputs, const std::string& out_dir,
                  const std::vector<std::string>& presets, const std::optional<std::vector<long long>>& tier_list,
                  int jobs, const std::string& normal, const std::string& rules_file, const std::string& rules_text,
                  const std::optional<std::pair<int, int>>& shard, const std::string& cache, bool cache_named,
                  bool force, bool replace, py::object progress, std::shared_ptr<Cancel> cancel) {
    require_input(inputs);
    const std::vector<fs::path> in_paths = paths_of(inputs);
    if (std::string why = mf::output_overlaps_input(out_dir, in_paths); !why.empty())
        throw Failure("UsageError", "usage", why);
    if (presets.empty()) throw Failure("UsageError", "usage", "no preset given");
    if (shard && (shard->second < 1 || shard->first < 0 || shard->first >= shard->second))
        throw Failure("UsageError", "usage",
                      "shard must be (I, N) with 0 <= I < N, not (" + std::to_string(shard->first) + ", " +
                          std::to_string(shard->second) + ")");
    std::string error;
    // Ascending, each once, in 1..65536 (`--tiers`' rule); they replace the presets' own.
    std::optional<std::vector<int>> tiers;
    if (tier_list && !(tiers = mf::check_tiers(*tier_list, "tiers", error)))
        throw Failure("UsageError", "usage", error);
    const auto color = color_context();
    const bool several = presets.size() > 1;
    std::vector<std::unique_ptr<mf::Ingestor>> ingestors;
    std::vector<RunOutcome> runs;
    std::set<std::string> taken;
    Watch watch(std::move(progress), std::move(cancel));
    auto add_run = [&](mf::Preset preset, const mf::rules::RuleConfig& rules, const fs::path& folder,
                       const std::string& label) {
        mf::IngestOptions opt;
        opt.out_dir = folder;
        opt.jobs = jobs;
        opt.rules = rules;
        opt.force = force;
        opt.replace = replace;
        if (!cache.empty()) {
            opt.cache_dir = fs::path(cache);
            if (std::string why = mf::cache_overlaps(*opt.cache_dir, opt.out_dir, in_paths); !why.empty())
                throw Failure("UsageError", "usage", why);
            // A folder the caller named must be a cache (or new); the default one, if foreign, is
            // left alone and the run goes on without it (process/ingest.cpp), as the CLI does.
            if (std::string why = mf::Cache::unusable(*opt.cache_dir); cache_named && !why.empty())
                throw Failure("UsageError", "usage", why);
        }
        if (!normal.empty()) opt.normal_override = mf::convention_from_name(normal);
        if (shard) {
            opt.shard = shard;
            opt.manifest_name = "manifest.shard-" + std::to_string(shard->first) + "-of-" +
                                std::to_string(shard->second) + ".json";
        }
        if (ingestors.empty())  // the pass's progress is the first run's (the others follow it set by set)
            opt.progress = [&watch](size_t done, size_t total, const std::string& name, const mf::MaterialResult&) {
                watch.report(done, total, name);
            };
        runs.push_back({label, opt.out_dir / opt.manifest_name, {}});
        ingestors.push_back(std::make_unique<mf::Ingestor>(std::move(preset), color, std::move(opt)));
    };
    for (const std::string& name : presets) {
        if (name.empty()) throw Failure("UsageError", "usage", "an empty preset name");
        mf::Preset preset = preset_of(name);
        const mf::rules::RuleConfig rules = rules_of(preset, rules_file, rules_text);
        const auto folder = mf::preset_output_folder(out_dir, preset.name, presets.size(), taken, error);
        if (!folder) throw Failure("UsageError", "usage", name + ": " + error);
        const std::vector<int> preset_tiers = tiers ? *tiers : preset.tiers;
        const std::string prefix = several ? preset.name + "/" : "";
        if (preset_tiers.empty()) add_run(preset, rules, *folder, several ? preset.name : "");
        for (const int tier : preset_tiers)
            add_run(mf::with_max_size(preset, tier), rules, *folder / std::to_string(tier),
                    prefix + std::to_string(tier));
    }
    std::vector<const mf::Ingestor*> all;
    std::vector<fs::path> outputs;
    for (size_t i = 0; i < ingestors.size(); ++i) {
        all.push_back(ingestors[i].get());
        outputs.push_back(runs[i].manifest.parent_path());
    }
    bool interrupted = false;
    run_watched(watch, [&] {
        std::vector<mf::IngestResult> results = mf::Ingestor::run_together(all, mf::Batch::find(in_paths, outputs));
        for (size_t i = 0; i < results.size(); ++i) {
            interrupted = interrupted || results[i].interrupted;
            runs[i].result = std::move(results[i]);
        }
    });
    watch.raise_if_stopped(interrupted);
    py::list out;
    for (RunOutcome& run : runs) {
        const mf::IngestResult& r = run.result;
        if (!r.error.empty())
            throw Failure(r.usage_error ? "UsageError" : "OutputError",
                          r.usage_error ? std::string("usage") : std::string(mf::code::output_write_failed), r.error);
        py::dict d;
        d["folder"] = run.folder;
        d["manifest"] = run.manifest.string();
        d["notes"] = r.notes;
        d["cache_hits"] = r.cache_hits;
        d["cache_misses"] = r.cache_misses;
        d["cache_problems"] = r.cache_problems;
        out.append(std::move(d));
    }
    return out;
}

// `matforge.read_manifest`: a manifest as the library reads it (checked member by member), as
// it would write it.
py::object read_manifest(const std::string& path) {
    std::string error;
    const auto m = mf::manifest::read_manifest(path, error);
    if (!m) throw Failure("ManifestError", "manifest", error);
    return to_py(mf::manifest::to_json(*m));
}

// `matforge.plan`: `matforge plan`'s work list (tools/matforge/cmd_plan.cpp), written to `out`
// when given.
py::object plan(const std::vector<std::string>& inputs, const std::string& preset_name, const std::string& rules_file,
                const std::string& rules_text, int shards, const std::string& changed_since, const std::string& out) {
    require_input(inputs);
    if (shards < 1) throw Failure("UsageError", "usage", "shards must be at least 1");
    const mf::Preset preset = preset_of(preset_name);
    if (!preset.tiers.empty())
        throw Failure("UsageError", "usage",
                      preset_name + ": max_size is a list of tiers; a plan's action keys are those of one max_size: "
                                    "plan each tier with a preset file of that max_size");
    const mf::rules::RuleConfig rules = rules_of(preset, rules_file, rules_text);
    const auto color = color_context();
    std::map<std::string, std::string> earlier;
    std::string error;
    if (!changed_since.empty() && !mf::manifest::read_manifest(
                                      changed_since,
                                      [&](mf::manifest::Material&& m, std::string&) {
                                          earlier[m.name] = m.key;
                                          return true;
                                      },
                                      error))
        throw Failure("ManifestError", "manifest", "changed_since: " + error);
    json result;
    Watch watch(py::none(), nullptr);
    run_watched(watch, [&] {
        const std::vector<fs::path> in_paths = paths_of(inputs);
        const mf::Batch batch = mf::Batch::find(in_paths);
        if (!out.empty())
            if (std::string why = mf::written_file_conflict(out, in_paths, batch.sets); !why.empty())
                throw Failure("UsageError", "usage", "out: " + why);
        mf::Plan p = mf::Plan::of(batch, preset.name, mf::context_digest(preset, rules, *color), shards,
                                  changed_since.empty() ? nullptr : &earlier);
        if (!changed_since.empty()) p.changed_since = changed_since;
        result = p.to_json();
        const std::string text = mf::json_text(result);
        if (!out.empty() &&
            !mf::write_file_atomic(out, std::span(reinterpret_cast<const unsigned char*>(text.data()), text.size()),
                                   error))
            throw Failure("OutputError", std::string(mf::code::output_write_failed), error);
    });
    watch.raise_if_stopped(true);
    return to_py(result);
}

// `matforge.merge`: `matforge merge` (tools/matforge/cmd_merge.cpp): the shards' manifests as the
// one manifest (and library) one run writes, beside them. A part whose shard's run failed
// (validate::run_fails under `fail_on`) is refused, naming it, unless `keep_errors`.
py::object merge(const std::vector<std::string>& parts, const std::string& out_file, const std::string& fail_on_name,
                 bool keep_errors) {
    if (parts.empty()) throw Failure("UsageError", "usage", "no part given");
    std::error_code ec;
    const fs::path out = fs::weakly_canonical(fs::absolute(out_file, ec), ec);
    const fs::path dir = out.parent_path();
    for (const auto& part : parts) {
        const fs::path p = fs::weakly_canonical(fs::absolute(part, ec), ec);
        if (p == out) throw Failure("UsageError", "usage", "out " + out_file + " is one of the parts");
        if (p.parent_path() != dir)
            throw Failure("UsageError", "usage",
                          "out " + out_file + " is not in the folder of the part " + part +
                              ": the merged manifest goes beside its parts, whose paths are relative to it");
    }
    const mf::validate::FailOn fail_on = mf::cli::fail_on_of(fail_on_name);
    std::string error;
    std::vector<std::string> failed_parts;  // "<part>: <set>: <CODE> <message>", one per failed part
    Watch watch(py::none(), nullptr);
    run_watched(watch, [&] {
        auto spool = mf::manifest::MaterialSpool::open(dir, error);
        if (!spool) throw Failure("OutputError", std::string(mf::code::output_write_failed), error);
        std::map<size_t, std::string> first_failure;  // part -> its first failing set or input
        auto fails = [&](const mf::Finding& f) {
            mf::validate::Summary s;
            mf::validate::add_material(s, {f});
            return mf::validate::run_fails(s, fail_on);
        };
        mf::manifest::PartObserver seen;
        seen.material = [&](size_t i, const mf::manifest::Material& m) {
            for (const mf::Finding& f : m.findings)
                if (fails(f)) {
                    first_failure.emplace(i, m.name + ": " + f.code + " " + f.message);
                    break;
                }
        };
        seen.head = [&](size_t i, const mf::manifest::Manifest& head) {
            if (!head.failures.empty())
                first_failure.emplace(i, head.failures[0].source + ": " + head.failures[0].code + " " +
                                             head.failures[0].message);
        };
        auto merged = mf::manifest::merge_shards(parts, dir, *spool, error, seen);
        if (!merged) throw Failure("UsageError", "usage", error);
        for (const auto& [i, first] : first_failure) failed_parts.push_back(parts[i] + ": " + first);
        if (!failed_parts.empty() && !keep_errors) return;
        if (!mf::write_library(
                *spool, dir,
                [&](const std::string& rel, std::span<const unsigned char> b, std::string& e) {
                    return mf::write_file_atomic(dir / rel, b, e);
                },
                [&](const std::string& rel, const mf::ByteProducer& p, std::string& e) {
                    return mf::write_file_atomic(dir / rel, p, e);
                },
                merged->library, error))
            throw Failure("OutputError", std::string(mf::code::output_write_failed), error);
        if (!mf::write_file_atomic(
                out, [&](const mf::ByteSink& sink) { return spool->write_manifest(*merged, sink, error); }, error))
            throw Failure("OutputError", std::string(mf::code::output_write_failed), error);
    });
    if (!failed_parts.empty() && !keep_errors) {
        std::string text = "not merged: the run of a shard failed (fail_on " + fail_on_name + ")";
        for (const auto& f : failed_parts) text += "\n  " + f;
        throw Failure("MergeError", "shard_failed", text);
    }
    py::dict d;
    d["manifest"] = out.string();
    d["failed_parts"] = failed_parts;
    return d;
}

// The libraries that read inputs and decide output bytes, as loaded now (`matforge --version`'s
// list but the preview's Vulkan headers): OpenImageIO through the image module, which this loads.
std::vector<std::string> libraries() {
    return {mf::image_library_versions(), mf::color_library_version(), mf::texture::encoder_versions(),
            mf::archive_library_version(), mf::crypto_library_version()};
}

// A run's counts (validate/verdict.hpp add_material, its one owner): each material's findings as
// (code, severity) pairs, and the inputs not processed.
py::dict summary(const std::vector<std::vector<std::pair<std::string, std::string>>>& materials, int failures) {
    mf::validate::Summary s;
    for (const auto& findings : materials) {
        std::vector<mf::Finding> fs;
        for (const auto& [code, severity] : findings) {
            mf::Finding f;
            f.code = code;
            f.severity = mf::severity_from_name(severity).value_or(mf::Severity::info);
            fs.push_back(std::move(f));
        }
        mf::validate::add_material(s, fs);
    }
    s.failures = failures;
    py::dict d;
    d["error"] = s.error;
    d["warning"] = s.warning;
    d["info"] = s.info;
    d["failures"] = s.failures;
    d["incomplete"] = s.incomplete;
    return d;
}

// Whether those counts fail a run under `fail_on` (validate::run_fails: the exit code's rule).
bool run_fails(int error, int warning, int info, int failures, int incomplete, const std::string& fail_on) {
    const auto f = mf::validate::fail_on_from_name(fail_on);
    if (!f) throw Failure("UsageError", "usage", "fail_on must be error, warning, info or never, not " + fail_on);
    return mf::validate::run_fails({error, warning, info, failures, incomplete}, *f);
}

// Where an ingest keeps its result cache unless told: the CLI's rule ($MATFORGE_CACHE, else the
// XDG cache folder), "" when none can be named.
std::string default_cache() {
    const auto dir = mf::cli::cache_folder("");
    return dir ? dir->string() : std::string();
}

}  // namespace
}  // namespace mfpy

PYBIND11_MODULE(_core, m) {
    using namespace mfpy;
    m.doc() = "matforge's library (python/matforge wraps it: import matforge)";
    // Failure -> the exception class of python/matforge/_errors.py its kind names, with its code.
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const Failure& f) {
            const py::object cls = py::module_::import("matforge._errors").attr(f.kind.c_str());
            const py::object e = cls(f.message, f.code);
            PyErr_SetObject(cls.ptr(), e.ptr());
        }
    });
    py::class_<Cancel, std::shared_ptr<Cancel>>(m, "Cancel",
                                                "A token that stops the run it is given at its next set: "
                                                "cancel() from any thread (a UI's button, a signal handler)")
        .def(py::init<>())
        .def("cancel", &Cancel::cancel, "ask the run to stop")
        .def_property_readonly("cancelled", &Cancel::cancelled, "whether cancel() was called");
    m.def("version", [] { return std::string(mf::kGenerator); });
    m.def("presets", &mf::shipped_presets);
    m.def("libraries", &libraries);
    m.def("default_cache", &default_cache);
    m.def("summary", &summary, py::arg("materials"), py::arg("failures"));
    m.def("run_fails", &run_fails, py::arg("error"), py::arg("warning"), py::arg("info"), py::arg("failures"),
          py::arg("incomplete"), py::arg("fail_on"));
    m.def("discover", &discover, py::arg("inputs"), py::arg("preset"), py::arg("rules_file"), py::arg("rules_text"));
    m.def("validate", &validate, py::arg("inputs"), py::arg("preset"), py::arg("rules_file"), py::arg("rules_text"),
          py::arg("jobs"), py::arg("progress"), py::arg("cancel"));
    m.def("ingest", &ingest, py::arg("inputs"), py::arg("out"), py::arg("presets"), py::arg("tiers"), py::arg("jobs"),
          py::arg("normal_convention"), py::arg("rules_file"), py::arg("rules_text"), py::arg("shard"),
          py::arg("cache"), py::arg("cache_named"), py::arg("force"), py::arg("replace"), py::arg("progress"),
          py::arg("cancel"));
    m.def("read_manifest", &read_manifest, py::arg("path"));
    m.def("plan", &plan, py::arg("inputs"), py::arg("preset"), py::arg("rules_file"), py::arg("rules_text"),
          py::arg("shards"), py::arg("changed_since"), py::arg("out"));
    m.def("merge", &merge, py::arg("parts"), py::arg("out"), py::arg("fail_on"), py::arg("keep_errors"));
}
