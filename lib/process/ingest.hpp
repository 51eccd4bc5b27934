// Ingest: material sets -> engine-ready outputs + manifest.json (shared/spec/interface.md).
#pragma once
#include <filesystem>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "color/color.hpp"
#include "core/findings.hpp"
#include "pack/preset.hpp"
#include "process/sets.hpp"

namespace mf {

struct IngestOptions {
    std::filesystem::path out_dir;
    int jobs = 0;  // 0 = all cores
    std::optional<NormalConvention> normal_override;  // --normal-convention
    // Called after each set (from worker threads, serialized): done count, total, name, status.
    std::function<void(size_t done, size_t total, const std::string& name, const std::string& status)> progress;
};

// Decides the green convention of a normal map whose name is silent (validate's content
// detector). Returns {convention, confidence}; unknown when undecided.
using NormalDetector = std::function<std::pair<NormalConvention, double>(const Image& encoded,
                                                                          const Image* height)>;

struct MaterialResult {
    nlohmann::json manifest_entry;  // one element of manifest "materials"
    std::vector<Finding> findings;
    bool failed = false;            // nothing could be produced (goes to "failures")
    std::string failure_message;
};

struct IngestResult {
    nlohmann::json manifest;
    size_t materials = 0, failures = 0;
    std::optional<Severity> worst;
    std::string error;  // batch-level error (output folder unusable); empty when fine
};

class Ingestor {
public:
    Ingestor(Preset preset, std::shared_ptr<const ColorContext> color, IngestOptions opt);
    void set_normal_detector(NormalDetector d) { detector_ = std::move(d); }

    // One set; thread-safe. Writes its outputs under out_dir.
    MaterialResult process(const MaterialSource& src) const;
    // Finds the sets, processes them in parallel, writes manifest.json atomically.
    IngestResult run(const std::vector<std::filesystem::path>& inputs) const;

private:
    Preset preset_;
    std::shared_ptr<const ColorContext> color_;
    IngestOptions opt_;
    NormalDetector detector_;
};

}  // namespace mf
