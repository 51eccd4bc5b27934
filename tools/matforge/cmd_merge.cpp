// matforge merge <manifest.json>... -o <manifest.json>
// The manifests of the shards of one run (`ingest --shard I/N` into one output folder) become the
// manifest one unsharded run writes, byte for byte, with the run's library.gltf (a shard sees
// only its part, so the library is written here) beside it. A part whose run failed (an input
// not processed, a finding at --fail-on) is a shard to run again: the merge refuses, naming it,
// unless --keep-errors takes the parts as they are (and then fails as that one run would).
#include <algorithm>
#include <map>
#include <memory>

#include "command.hpp"
#include "core/files.hpp"
#include "core/json.hpp"
#include "manifest/manifest.hpp"
#include "manifest/spool.hpp"
#include "options.hpp"
#include "process/material_file.hpp"
#include "validate/verdict.hpp"

namespace mf::cli {
namespace {

struct MergeArgs {
    std::vector<std::string> inputs;
    std::string out;
    std::string fail_on = "error";
    bool keep_errors = false;
};

// One part's verdict, as its shard's run gave it: what failed it, and the first of those.
struct PartVerdict {
    std::string shard;  // "shard I of N"
    int failing = 0;    // sets with a finding that fails the run, and inputs not processed
    std::string first;  // "<set>: <CODE> <message>"
};

// Whether this finding alone fails a run (validate::run_fails owns the rule).
bool finding_fails(const Finding& f, validate::FailOn fail_on) {
    validate::Summary s;
    validate::add_material(s, {f});
    return validate::run_fails(s, fail_on);
}

// One line per failing part: "shard 1 of 3 (manifest.shard-1-of-3.json): 1 set failed, first
// Net004A: UNREADABLE_FILE ...".
std::string failed_parts_text(const std::vector<std::string>& paths, const std::map<size_t, PartVerdict>& parts) {
    std::string text;
    for (const auto& [i, v] : parts)
        if (v.failing > 0)
            text += "\n  " + v.shard + " (" + paths[i] + "): " + std::to_string(v.failing) +
                    (v.failing == 1 ? " set" : " sets") + " failed, first " + v.first;
    return text;
}

ExitCode run_merge(const MergeArgs& a) {
    // The manifest's paths are relative to its folder: the library goes there, built from the
    // materials' .gltf files the shards wrote. The materials pass through a temporary file there
    // (manifest/spool.hpp): the merge of 100,000 sets holds an index, not their entries.
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path out = fs::weakly_canonical(fs::absolute(a.out, ec), ec);
    const fs::path dir = out.parent_path();
    for (const auto& part : a.inputs)  // the merged manifest never replaces one of its parts
        if (fs::weakly_canonical(fs::absolute(part, ec), ec) == out)
            return fail("merge", "-o " + a.out + " is one of the parts; name the run's manifest.json");
    // The parts' paths, like the merged manifest's, are relative to the output folder the shards
    // wrote: the merged manifest goes there, beside them.
    for (const auto& part : a.inputs)
        if (const fs::path p = fs::weakly_canonical(fs::absolute(part, ec), ec); p.parent_path() != dir)
            return fail("merge", "-o " + a.out + " is not in the folder of the part " + part + " (" +
                                     p.parent_path().string() +
                                     "): the merged manifest goes beside its parts, whose paths are relative to it");
    // The materials pass through a temporary file there (manifest/spool.hpp): the merge of
    // 100,000 sets holds an index, not their entries.
    std::string error;
    auto spool = manifest::MaterialSpool::open(dir, error);
    if (!spool) return fail("merge", error, ExitCode::findings);
    // Each part judged as its shard's run was: what fails a run (validate::run_fails) fails the part.
    const validate::FailOn fail_on = fail_on_of(a.fail_on);
    std::map<size_t, PartVerdict> parts;
    validate::Summary all;
    manifest::PartObserver seen;
    seen.material = [&](size_t i, const manifest::Material& m) {
        validate::add_material(all, m.findings);
        for (const Finding& f : m.findings)
            if (finding_fails(f, fail_on)) {
                PartVerdict& v = parts[i];
                if (v.failing++ == 0) v.first = m.name + ": " + f.code + " " + f.message;
                break;
            }
    };
    seen.head = [&](size_t i, const manifest::Manifest& head) {
        PartVerdict& v = parts[i];
        if (head.shard)
            v.shard = "shard " + std::to_string(head.shard->index) + " of " + std::to_string(head.shard->count);
        all.failures += static_cast<int>(head.failures.size());
        for (const InputFailure& f : head.failures)
            if (v.failing++ == 0) v.first = f.source + ": " + f.code + " " + f.message;
    };
    auto merged = manifest::merge_shards(a.inputs, dir, *spool, error, seen);
    if (!merged) return fail("merge", error);
    const auto failed = std::count_if(parts.begin(), parts.end(), [](const auto& p) { return p.second.failing > 0; });
    if (failed > 0 && !a.keep_errors)
        return fail("merge",
                    "not merged: the run of " + std::string(failed == 1 ? "a shard" : "shards") +
                        " failed (--fail-on " + a.fail_on + ")" + failed_parts_text(a.inputs, parts) +
                        "\nfix what is named and run those shards again (`matforge plan --commands` prints each "
                        "one's line), then merge; or merge with --keep-errors to write the manifest one run "
                        "would (exit 1)",
                    ExitCode::findings);
    if (!write_library(
            *spool, dir,
            [&](const std::string& rel, std::span<const unsigned char> b, std::string& e) {
                return write_file_atomic(dir / rel, b, e);
            },
            [&](const std::string& rel, const ByteProducer& p, std::string& e) {
                return write_file_atomic(dir / rel, p, e);
            },
            merged->library, error))
        return fail("merge", error, ExitCode::findings);
    if (!write_file_atomic(
            a.out, [&](const ByteSink& sink) { return spool->write_manifest(*merged, sink, error); }, error))
        return fail("merge", error, ExitCode::findings);
    if (failed > 0) say("merge", "merged with errors (--keep-errors):" + failed_parts_text(a.inputs, parts));
    return verdict_exit(validate::run_fails(all, fail_on));
}

const Register register_merge{
    {"merge", 35,
     [](CLI::App& sub) -> std::function<ExitCode()> {
         auto a = std::make_shared<MergeArgs>();
         sub.add_option("manifests", a->inputs, "the shards' manifests (ingest --shard I/N)")->required();
         sub.add_option("-o,--out", a->out, "the merged manifest.json (written atomically)")->required();
         add_fail_on(sub, a->fail_on);
         sub.add_flag("--keep-errors", a->keep_errors,
                      "merge parts whose shard's run failed (a set not processed, a finding at --fail-on) as "
                      "they are, as one run would write them, and exit 1; without it such a merge is refused, "
                      "naming the shards to run again");
         return [a] { return run_merge(*a); };
     },
     "merge the manifests of sharded ingests into the manifest of one run"}};

}  // namespace
}  // namespace mf::cli
