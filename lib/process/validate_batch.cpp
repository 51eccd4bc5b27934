#include "process/validate_batch.hpp"

#include <algorithm>
#include <fstream>
#include <mutex>

#include "base/interrupt.hpp"
#include "base/parallel.hpp"
#include "core/json.hpp"
#include "core/version.hpp"
#include "plan/plan.hpp"
#include "sets/sets.hpp"

namespace mf {
namespace {

struct SetOutcome {
    manifest::Material report;
    bool failed = false;
    std::string failure;
};

SetOutcome validate_one(const MaterialSource& src, const Preset& preset, const rules::RuleConfig& rules) {
    SetOutcome out;
    SetPlan plan = plan_set(src, PlanOptions{&preset, &rules, PlanMode::stream, nullptr});
    if (plan.failure) {
        out.failed = true;
        out.failure = std::move(*plan.failure);
        return out;
    }
    out.report = material_entry(plan, src.name, src.display, rules);
    return out;
}

}  // namespace

std::optional<rules::RuleConfig> load_rule_config(const Preset& preset, const std::string& rules_file,
                                                  std::string& error) {
    auto cfg = rules::RuleConfig::from_json(preset.validate, error);
    if (!cfg) {
        error = "preset '" + preset.name + "' validate block: " + error;
        return std::nullopt;
    }
    if (rules_file.empty()) return cfg;
    // Depth-limited, never a FIFO or a device; the error names the file.
    const auto j = read_json_file(rules_file, error);
    if (!j) {
        error = "the rules file " + error;
        return std::nullopt;
    }
    auto layered = rules::RuleConfig::from_json(*j, error, *cfg);
    if (!layered) error = rules_file + ": " + error;
    return layered;
}

manifest::Manifest validate_batch(const Batch& batch, const Preset& preset, const ValidateBatchOptions& opt) {
    manifest::Manifest report;
    report.generator = std::string(kGenerator);
    report.preset = preset.name;
    report.normal_convention = preset.normal_convention;
    report.thresholds = rules::threshold_table(opt.rules.thresholds);
    const std::vector<MaterialSource>& sets = batch.sets;
    std::vector<SetOutcome> outcomes(sets.size());
    std::mutex progress_mutex;
    size_t done = 0;
    parallel_for(sets.size(), opt.jobs, [&](size_t i) {
        if (stop_requested()) return;  // a signal asked to stop (the command reports it)
        try {
            outcomes[i] = validate_one(sets[i], preset, opt.rules);
        } catch (const std::exception& e) {
            outcomes[i].failed = true;
            outcomes[i].failure = sets[i].display + ": internal error: " + e.what();
        }
        if (opt.progress) {
            const std::lock_guard lock(progress_mutex);
            opt.progress(++done, sets.size(), sets[i].name);
        }
    });
    for (size_t i = 0; i < sets.size(); ++i) {
        if (outcomes[i].failed)
            report.failures.push_back({sets[i].display, std::string(code::unreadable_file), outcomes[i].failure});
        else report.materials.push_back(std::move(outcomes[i].report));
    }
    for (const auto& f : batch.failures) report.failures.push_back(f);
    std::stable_sort(report.materials.begin(), report.materials.end(),
                     [](const auto& a, const auto& b) { return a.name < b.name; });
    return report;
}

}  // namespace mf
