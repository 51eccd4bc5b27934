// Ingest: material sets -> engine-ready outputs + manifest.json (docs/interface.md).
// Per set: plan_set (decode mode) -> canonical planes -> packed outputs written atomically ->
// the set's manifest entry; the batch writes manifest.json last.
#pragma once
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "base/budget.hpp"
#include "color/color.hpp"
#include "findings/findings.hpp"
#include "findings/rules.hpp"
#include "manifest/manifest.hpp"
#include "preset/preset.hpp"
#include "process/batch.hpp"
#include "sets/sets.hpp"
#include "validate/verdict.hpp"

namespace mf {

class SetShare;    // process/share.hpp
class SpareTasks;  // base/parallel.hpp

struct MaterialResult {
    manifest::Material entry;            // one element of the manifest's "materials"
    std::optional<std::string> failure;  // nothing could be produced (goes to "failures")
};

struct IngestOptions {
    std::filesystem::path out_dir;
    int jobs = 0;                                     // 0 = all cores
    std::optional<NormalConvention> normal_override;  // --normal-convention
    rules::RuleConfig rules;                          // validation thresholds, severities, suppressions
    // Cap on the estimated decoded bytes of the sets in flight (0 = no cap). A set larger than
    // the cap runs alone.
    uint64_t memory_budget = uint64_t{1} << 30;
    // --shard I/N: only the sets process/work's assign_shards gives shard I of N, and the
    // manifest is written as `manifest_name` (the shards of one run share the output folder;
    // `matforge merge` joins their manifests).
    std::optional<std::pair<int, int>> shard;
    std::string manifest_name = "manifest.json";
    // --force: replace a manifest.json matforge did not write, and files in the way of outputs
    // that no earlier run of ours wrote (store/output_dir.hpp).
    bool force = false;
    // --replace: write into a folder whose manifest lists another preset's outputs (they are
    // replaced, and removed where this preset does not write them); refused without it.
    bool replace = false;
    // The result cache (store/cache.hpp): an unchanged set (same file contents, preset, rules,
    // OCIO config, matforge version) is restored from it instead of decoded and encoded again.
    // nullopt: no cache (--no-cache).
    std::optional<std::filesystem::path> cache_dir;
    // Called after each set (from worker threads, serialized): done count, total, name, result.
    std::function<void(size_t done, size_t total, const std::string& name, const MaterialResult& result)> progress;
};

// A material of the run as its caller reports it: its name and its findings counted.
struct MaterialTally {
    std::string name;
    validate::Summary findings;  // error, warning, info; incomplete
};

struct IngestResult {
    // The manifest written, but for its materials (they go from a temporary file into the file,
    // never all in memory: manifest/spool.hpp); those are tallied in `materials`, by name.
    manifest::Manifest manifest;
    std::vector<MaterialTally> materials;
    std::string error;               // batch-level error (output folder unusable); empty when fine
    bool usage_error = false;        // `error` is about the choice of output folder (exit 2)
    bool interrupted = false;        // stopped by a signal (base/interrupt.hpp): no manifest written
    std::vector<std::string> notes;  // outputs of earlier runs removed or kept (output_dir.hpp)
    // Sets restored from the cache, sets computed, and what went wrong with the cache (a corrupt
    // blob, a full disk: the cache turned itself off), one line each.
    size_t cache_hits = 0, cache_misses = 0;
    std::vector<std::string> cache_problems;
};

// The output folder of a preset in a run into `out` of `presets` presets: `out` itself for one;
// <out>/<the preset's name> for several (ingest --preset a,b: a complete folder each, what that
// preset alone writes into it), so the name must be one plain path component and no two presets
// of the run may share it (`taken` collects the names). nullopt + `error` saying which.
std::optional<std::filesystem::path> preset_output_folder(const std::filesystem::path& out,
                                                          const std::string& preset_name, size_t presets,
                                                          std::set<std::string>& taken, std::string& error);

class Ingestor {
public:
    Ingestor(Preset preset, std::shared_ptr<const ColorContext> color, IngestOptions opt);

    // Finds the sets (Batch::find, never in the output folder), processes them in parallel,
    // writes manifest.json atomically. Thread-safe: everything a run changes lives in its
    // PresetRun, not in the Ingestor.
    IngestResult run(const std::vector<std::filesystem::path>& inputs) const;

    // Several ingestors (ingest --preset a,b: one per preset, each with its own output folder;
    // ingest --tiers: one per tier, the preset with that max_size)
    // over one batch (found once, with every ingestor's output folder excluded) in one pass: each
    // set is planned by every ingestor in turn on one worker, its maps decoded once
    // (plan/plan.hpp's PlanShare), and the outputs of those plans written as one list of tasks,
    // largest first, on that worker and a second thread while a core is idle (two ingestors at
    // a time: ingest.cpp kPresetsAtOnce); an output whose pixels and encoding equal one another
    // ingestor encodes for that set is encoded once. Each result, and every file, is what that
    // ingestor's run() gives alone. The first ingestor's jobs, memory budget, shard and progress
    // serve the pass.
    static std::vector<IngestResult> run_together(const std::vector<const Ingestor*>& ingestors, Batch batch);

private:
    Preset preset_;
    std::shared_ptr<const ColorContext> color_;
    IngestOptions opt_;
    // The preset's text but for max_size, and its normal convention: a block-compressed output of
    // two ingestors of equal keys (the tiers of one preset), equal size and equal planes is
    // encoded once in run_together (process/share.hpp BlockSource).
    std::string encoding_key_;
    // One preset's part of a pass (its output folder, claims, cache, spool, tallies; open(),
    // record() after each set, finish()): ingest.cpp.
    struct PresetRun;
    // One preset's part of one set, from begin() to end(): ingest.cpp.
    struct SetWork;
    // What a set's plan takes of its pass: the budget its decoded maps lease from (null: none, or
    // an earlier plan of the set holds the set's lease), and whether a core is idle now.
    struct SetStage {
        MemoryBudget* budget = nullptr;
        std::function<bool()> spare_core;
    };
    // One set of `run`, in three steps. begin(): restored from the run's cache (its result), or
    // planned: validated (every rule, from the decoded pixels: each file is decoded once),
    // converted to planes. post_outputs(): each output to pack, encode and write through the
    // run's output folder, a task on `tasks` (write_one). end(): once the tasks are done, the
    // material files and the set's result (kept in the cache). `share`: null for a run alone.
    std::unique_ptr<SetWork> begin(const MaterialSource& src, const SetStage& stage, PresetRun& run,
                                   SetShare* share) const;
    void post_outputs(SetWork& work, SpareTasks& tasks) const;
    void write_one(SetWork& work, size_t i) const;  // the set's i-th wanted output
    MaterialResult end(SetWork& work) const;
    MaterialResult finish_outputs(SetWork& work) const;
};

}  // namespace mf
