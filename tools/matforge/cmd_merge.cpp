// matforge merge <manifest.json>... -o <manifest.json>
// The manifests of the shards of one run (`ingest --shard I/N` into one output folder) become the
// manifest one unsharded run writes, byte for byte, with the run's library.gltf (a shard sees
// only its part, so the library is written here) beside it.
#include <memory>

#include "command.hpp"
#include "core/files.hpp"
#include "core/json.hpp"
#include "manifest/manifest.hpp"
#include "manifest/spool.hpp"
#include "process/material_file.hpp"

namespace mf::cli {
namespace {

struct MergeArgs {
    std::vector<std::string> inputs;
    std::string out;
};

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
    auto merged = manifest::merge_shards(a.inputs, dir, *spool, error);
    if (!merged) return fail("merge", error);
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
    return ExitCode::ok;
}

const Register register_merge{
    {"merge", 35,
     [](CLI::App& sub) -> std::function<ExitCode()> {
         auto a = std::make_shared<MergeArgs>();
         sub.add_option("manifests", a->inputs, "the shards' manifests (ingest --shard I/N)")->required();
         sub.add_option("-o,--out", a->out, "the merged manifest.json (written atomically)")->required();
         return [a] { return run_merge(*a); };
     },
     "merge the manifests of sharded ingests into the manifest of one run"}};

}  // namespace
}  // namespace mf::cli
