// The materials of a run on their way into manifest.json, kept as their manifest text in a
// temporary file (core/spool) with a small index in memory: ingest adds each set's entry when the
// set is done, merge each shard's entries as it reads them, and the manifest is written from the
// file in name order. A library of 100,000 sets then holds about 100 bytes a set (name, glTF
// path, index), not its entries (kilobytes each) nor the manifest's text.
#pragma once
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "core/files.hpp"
#include "core/spool.hpp"
#include "manifest/manifest.hpp"

namespace mf::manifest {

class MaterialSpool {
public:
    struct Entry {
        std::string name;
        std::string gltf;  // the material's .gltf (material_files), "" when none: library.gltf's input
        uint32_t piece = 0;
        int part = 0;
    };
    // The temporary file in `dir` (see core/spool.hpp). nullptr + `error`.
    static std::unique_ptr<MaterialSpool> open(const std::filesystem::path& dir, std::string& error);

    // Thread-safe. `part` says where the entry came from (merge: which shard), for sort()'s answer.
    bool add(const Material& m, std::string& error, int part = 0);
    size_t size() const;

    struct Duplicate {
        std::string name;
        int first_part = 0, second_part = 0;
    };
    // After the last add(): the index in name order (the order a manifest lists materials). The
    // first name added twice, if any (a manifest names each material once).
    std::optional<Duplicate> sort();
    // After sort(), in name order.
    const std::vector<Entry>& entries() const { return entries_; }
    // Each material read back from the file, in name order; false + `error` (or `fn`'s false).
    bool for_each(const std::function<bool(Material&&)>& fn, std::string& error) const;
    // The manifest's text: `head`'s members (its materials ignored) with the spooled materials in
    // name order; the bytes manifest_text gives for the same manifest.
    bool write_manifest(const Manifest& head, const ByteSink& sink, std::string& error) const;

private:
    explicit MaterialSpool(std::unique_ptr<TextSpool> text) : text_(std::move(text)) {}
    std::unique_ptr<TextSpool> text_;
    mutable std::mutex mutex_;
    std::vector<Entry> entries_;
};

// `matforge merge`: the shard manifests at `paths` (all in `dir`, the run's output folder) read
// one material at a time into `spool` (then sorted), checked to make one run (merge_heads), one
// material in two shards refused, and every part complete: it holds as many materials as its
// shard was given sets (each set a material, or a failure when nothing of it could be read),
// and every file a material lists is inside `dir`, a regular file there, and hashes to its
// sha256. The merged manifest's head (its materials are the spool's), or nullopt + `error`
// naming the files.
// `seen`, when given, is shown each part's head (its failures and shard) and each of its
// materials as they are read: what the caller needs to judge each shard (cmd_merge's verdict).
struct PartObserver {
    std::function<void(size_t part, const Manifest& head)> head;
    std::function<void(size_t part, const Material& m)> material;
};
std::optional<Manifest> merge_shards(const std::vector<std::string>& paths, const std::filesystem::path& dir,
                                     MaterialSpool& spool, std::string& error, const PartObserver& seen = {});

}  // namespace mf::manifest
