// `matforge validate`: discovery and every rule over each set, writing nothing but the report.
#pragma once
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "findings/rules.hpp"
#include "manifest/manifest.hpp"
#include "preset/preset.hpp"
#include "process/batch.hpp"

namespace mf {

struct ValidateBatchOptions {
    int jobs = 0;  // 0 = all cores
    rules::RuleConfig rules;
    // Called after each set (from worker threads, serialized): sets done, total, the set's name.
    std::function<void(size_t done, size_t total, const std::string& name)> progress;
};

// The preset's "validate" block, then the JSON file `rules_file` (if not empty) layered over it.
// nullopt + `error` naming the file on any problem (a configuration error: exit 2).
std::optional<rules::RuleConfig> load_rule_config(const Preset& preset, const std::string& rules_file,
                                                  std::string& error);

// The sets of `batch` validated in parallel, as a manifest with no outputs (what ingest would
// record of each set but what it writes: the report writers take either, report/formats.hpp):
// materials in name order with their sources as the user gave them, failures after; the
// preset, its normal convention and the thresholds applied.
manifest::Manifest validate_batch(const Batch& batch, const Preset& preset, const ValidateBatchOptions& opt);

}  // namespace mf
