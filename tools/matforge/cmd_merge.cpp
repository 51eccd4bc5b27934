// matforge merge <manifest.json>... -o <manifest.json>
// The manifests of the shards of one run (`ingest --shard I/N` into one output folder) become the
// manifest one unsharded run writes, byte for byte, with the run's library.gltf (a shard sees
// only its part, so the library is written here) beside it.
#include <memory>

#include "command.hpp"
#include "core/files.hpp"
#include "core/json.hpp"
#include "manifest/manifest.hpp"
#include "process/material_file.hpp"

namespace mf::cli {
namespace {

struct MergeArgs {
    std::vector<std::string> inputs;
    std::string out;
};

ExitCode run_merge(const MergeArgs& a) {
    std::vector<manifest::Manifest> parts;
    for (const std::string& f : a.inputs) {
        std::string error;
        auto m = manifest::read_manifest(f, error);
        if (!m) return fail("merge", error);
        parts.push_back(std::move(*m));
    }
    std::string error;
    auto merged = manifest::merge(parts, a.inputs, error);
    if (!merged) return fail("merge", error);
    // The manifest's paths are relative to its folder: the library goes there, built from the
    // materials' .gltf files the shards wrote.
    const std::filesystem::path dir = std::filesystem::absolute(a.out).parent_path();
    if (!write_library(
            *merged, dir,
            [&](const std::string& rel, std::span<const unsigned char> b, std::string& e) {
                return write_file_atomic(dir / rel, b, e);
            },
            error))
        return fail("merge", error, ExitCode::findings);
    const std::string text = manifest::manifest_text(*merged);
    if (!write_file_atomic(a.out, std::span(reinterpret_cast<const unsigned char*>(text.data()), text.size()), error))
        return fail("merge", error, ExitCode::findings);
    return ExitCode::ok;
}

const Register reg{
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
