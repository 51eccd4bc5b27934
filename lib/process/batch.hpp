// A run's material sets, found once: what ingest (every preset of a run), plan and validate work
// on. Discovery, the sets' sizes, the order a pass starts them in and the split into shards are
// decided here and nowhere else; `Plan` is the typed work list `matforge plan` writes, the
// contract with a render farm (docs/plan.schema.json).
#pragma once
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "findings/findings.hpp"
#include "image/image.hpp"
#include "sets/sets.hpp"

namespace mf {

struct Batch {
    std::vector<MaterialSource> sets;    // discovery order (find_material_sets)
    std::vector<uint64_t> bytes;         // each set's size (process/work.hpp set_bytes), read once
    std::vector<InputFailure> failures;  // inputs that gave no set, or could not be read
    std::vector<std::string> skipped;    // output folders of earlier runs under the inputs, one line each
    std::string output_conflict;         // an output folder that is a set's own folder (a usage error)
    // The run's read memo (image/image.hpp): headers read while finding the sets and planning
    // them are remembered until the batch is gone.
    ReadScope reads;

    // Every set under `inputs`, never inside `outputs` (the run's output folders, where they lie
    // inside an input).
    static Batch find(const std::vector<std::filesystem::path>& inputs,
                      const std::vector<std::filesystem::path>& outputs = {});

    // Set indices by decreasing size, ties in discovery order (longest processing time first: a
    // 4K set started last would leave the other threads idle while it runs alone).
    std::vector<size_t> largest_first() const;
    // The library split into `n` shards: shard[i] in [0, n) for set i (process/work.hpp
    // assign_shards: balanced by size, stable).
    struct Split {
        int n = 1;
        std::vector<int> shard;
    };
    Split split(int n) const;
    // The digest of `split` under `context` (process/work.hpp plan_digest): every shard of one
    // run records it, `merge` compares them.
    std::string split_digest(const Split& split, const std::string& context) const;
    // Keeps only the sets `split` gives shard `index`, in order.
    void keep_shard(const Split& split, int index);
};

// `matforge plan`'s work list, version 1 (docs/plan.schema.json).
struct Plan {
    struct Set {
        std::string name, source;
        uint64_t bytes = 0;
        size_t files = 0;
        int shard = 0;
        std::optional<std::string> key;    // the action key (process/work.hpp), or
        std::optional<std::string> error;  // why a file of the set could not be read
    };
    std::string generator, preset, context, digest;  // digest: split_digest, what every shard records
    int shards = 1;
    std::vector<Set> sets;
    std::vector<InputFailure> failures;
    // --changed-since: the manifest compared with and the sets left out as unchanged.
    std::optional<std::string> changed_since;
    size_t unchanged = 0;

    // The plan of `batch` split into `shards` under `context` (process/work.hpp), each set's action
    // key read from its files. `earlier` (--changed-since: material name -> action key of an
    // earlier run's manifest): sets whose key is unchanged are left out and counted.
    static Plan of(const Batch& batch, const std::string& preset, const std::string& context, int shards,
                   const std::map<std::string, std::string>* earlier = nullptr);
    // Whether a file could not be read (an input without a set, a set without its key).
    bool unreadable() const;
    nlohmann::json to_json() const;
};

}  // namespace mf
