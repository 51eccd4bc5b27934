#include "process/validate_batch.hpp"

#include <algorithm>
#include <fstream>

#include "core/parallel.hpp"
#include "material/discovery.hpp"
#include "process/missing.hpp"
#include "process/sets.hpp"
#include "validate/validate.hpp"

namespace mf {
namespace {

struct SetOutcome {
    validate::MaterialReport report;
    bool failed = false;
    std::string failure;
};

SetOutcome validate_one(const MaterialSource& src, const Preset& preset, const validate::RuleConfig& rules) {
    SetOutcome out;
    out.report.name = src.name;
    out.report.source = src.display;
    auto& findings = out.report.findings;
    std::map<std::string, InputFile> opened;
    auto open = [&](const std::string& f) -> const InputFile& {
        auto it = opened.find(f);
        if (it == opened.end()) it = opened.emplace(f, src.open(f)).first;
        return it->second;
    };
    auto header = [&](const std::string& f) -> std::optional<HeaderInfo> {
        std::string err;
        auto info = read_info(open(f), err);
        if (!info) return std::nullopt;
        return HeaderInfo{info->width, info->height, info->channels, info->bit_depth, info->is_float};
    };
    const SetDiscovery d = discover_set(src.files, header, ChoicePolicy{preset.normal_convention, preset.max_size});
    findings = d.findings;

    std::vector<validate::MapInput> maps;
    std::set<Role> inputs_present;
    for (const auto& choice : d.choices) {
        std::vector<const Candidate*> order{&choice.chosen};
        for (const auto& r : choice.rejected) order.push_back(&r);
        for (const Candidate* c : order) {
            std::string err;
            if (auto m = validate::make_map_input(choice.role, open(c->file), c->file, c->match.normal, err)) {
                maps.push_back(std::move(*m));
                inputs_present.insert(choice.role);
                break;
            }
            findings.push_back({std::string(code::unreadable_file), Severity::error, std::string(role_name(choice.role)),
                                c->file, err + "; the file is skipped", {}});
        }
    }
    if (maps.empty()) {
        out.failed = true;
        out.failure = src.display + ": no map of the set could be read";
        return out;
    }
    validate::ValidateOptions vo;
    vo.material = src.name;
    auto checked = validate::validate_set(maps, rules, vo);
    findings.insert(findings.end(), checked.findings.begin(), checked.findings.end());

    // The roles the preset would get, to report what it would have to generate.
    std::set<Role> available;
    for (int ri = 0; ri < kOutputRoleCount; ++ri) {
        const Role r = static_cast<Role>(ri);
        for (const Provider& p : providers_of(r))
            if (inputs_present.count(p.from)) {
                available.insert(r);
                break;
            }
    }
    nlohmann::json constants = nlohmann::json::object();
    auto missing = missing_map_findings(preset, available, written_roles(preset, available), constants);
    findings.insert(findings.end(), missing.begin(), missing.end());
    validate::apply_config(findings, src.name, rules);
    return out;
}

}  // namespace

std::optional<validate::RuleConfig> load_rule_config(const Preset& preset, const std::string& rules_file,
                                                     std::string& error) {
    auto cfg = validate::RuleConfig::from_json(preset.validate, error);
    if (!cfg) {
        error = "preset '" + preset.name + "' validate block: " + error;
        return std::nullopt;
    }
    if (rules_file.empty()) return cfg;
    std::ifstream f(rules_file);
    if (!f) {
        error = rules_file + ": cannot open the rules file";
        return std::nullopt;
    }
    const auto j = nlohmann::json::parse(f, nullptr, false);
    if (j.is_discarded()) {
        error = rules_file + ": not valid JSON";
        return std::nullopt;
    }
    auto layered = validate::RuleConfig::from_json(j, error, *cfg);
    if (!layered) error = rules_file + ": " + error;
    return layered;
}

validate::Report validate_inputs(const std::vector<std::filesystem::path>& inputs, const Preset& preset,
                                 const ValidateBatchOptions& opt) {
    validate::Report report;
    std::vector<SourceFailure> source_failures;
    const auto sets = find_material_sets(inputs, {}, source_failures);
    std::vector<SetOutcome> outcomes(sets.size());
    parallel_for(sets.size(), opt.jobs, [&](size_t i) {
        try {
            outcomes[i] = validate_one(sets[i], preset, opt.rules);
        } catch (const std::exception& e) {
            outcomes[i].failed = true;
            outcomes[i].failure = sets[i].display + ": internal error: " + e.what();
        }
    });
    for (size_t i = 0; i < sets.size(); ++i) {
        if (outcomes[i].failed)
            report.failures.push_back({sets[i].display, std::string(code::unreadable_file), outcomes[i].failure});
        else
            report.materials.push_back(std::move(outcomes[i].report));
    }
    for (const auto& f : source_failures) report.failures.push_back({f.source, f.code, f.message});
    std::stable_sort(report.materials.begin(), report.materials.end(),
                     [](const auto& a, const auto& b) { return a.name < b.name; });
    return report;
}

}  // namespace mf
