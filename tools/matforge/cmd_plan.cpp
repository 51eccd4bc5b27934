// matforge plan <input>... -o plan.json [--preset NAME|FILE] [--rules FILE] [--shards N]
// The deterministic work list: every set with its size, its action key and, with --shards, the
// shard `ingest --shard I/N` gives it. Reads every input file once (to hash it), decodes nothing.
#include <memory>

#include "command.hpp"
#include "core/files.hpp"
#include "core/json.hpp"
#include "core/version.hpp"
#include "process/validate_batch.hpp"
#include "process/work.hpp"
#include "sets/sets.hpp"

namespace mf::cli {
namespace {

struct PlanArgs {
    std::vector<std::string> inputs;
    std::string out, preset = "gltf", rules_file;
    int shards = 1;
};

ExitCode run_plan(const PlanArgs& a) {
    if (std::string why = no_usable_input({a.inputs.begin(), a.inputs.end()}); !why.empty()) return fail("plan", why);
    std::string error;
    auto preset = load_preset(a.preset, error);
    if (!preset) return fail("plan", error);
    auto rules = load_rule_config(*preset, a.rules_file, error);
    if (!rules) return fail("plan", error);
    auto color = ColorContext::create(error);
    if (!color) return fail("plan", error);
    std::vector<InputFailure> failures;
    const std::vector<std::filesystem::path> inputs(a.inputs.begin(), a.inputs.end());
    std::vector<std::string> skipped;
    const auto sets = find_material_sets(inputs, {}, failures, nullptr, &skipped);
    for (const std::string& n : skipped) say("plan", "note: " + n);
    if (std::string why = written_file_conflict(a.out, inputs, sets); !why.empty()) return fail("plan", "-o " + why);
    const std::string context = context_digest(*preset, *rules, *color);
    std::vector<uint64_t> bytes;
    bytes.reserve(sets.size());
    for (const auto& s : sets) bytes.push_back(set_bytes(s));
    const std::vector<int> shard = assign_shards(sets, bytes, a.shards);
    nlohmann::json list = nlohmann::json::array();
    bool unreadable = !failures.empty();
    for (size_t i = 0; i < sets.size(); ++i) {
        nlohmann::json item{{"name", sets[i].name},
                            {"source", sets[i].display},
                            {"bytes", bytes[i]},
                            {"files", sets[i].files.size()},
                            {"shard", shard[i]}};
        if (const auto key = action_key(sets[i], context, error)) item["key"] = *key;
        else {
            item["error"] = error;
            unreadable = true;
        }
        list.push_back(std::move(item));
    }
    nlohmann::json fl = nlohmann::json::array();
    for (const auto& f : failures) fl.push_back(to_json(f));
    // `plan`: what every shard's manifest records (process/work.hpp plan_digest); merge refuses
    // parts of different plans.
    const nlohmann::json plan{{"plan_version", 1},
                              {"generator", kGenerator},
                              {"preset", preset->name},
                              {"context", context},
                              {"plan", plan_digest(sets, bytes, shard, a.shards, context)},
                              {"shards", a.shards},
                              {"sets", list},
                              {"failures", fl}};
    const std::string text = json_text(plan);
    if (!write_file_atomic(a.out, std::span(reinterpret_cast<const unsigned char*>(text.data()), text.size()), error))
        return fail("plan", error, ExitCode::findings);
    return unreadable ? ExitCode::findings : ExitCode::ok;
}

const Register register_plan{
    {"plan", 15,
     [](CLI::App& sub) -> std::function<ExitCode()> {
         auto a = std::make_shared<PlanArgs>();
         sub.add_option("inputs", a->inputs, "material folders, .zip files, or folders of many (recursive)")
             ->required();
         sub.add_option("-o,--out", a->out, "the work list (JSON)")->required();
         sub.add_option("--preset", a->preset, "preset the keys are for (shipped name or JSON file)")
             ->capture_default_str();
         sub.add_option("--rules", a->rules_file, "rule configuration the keys are for (docs/rules.md)");
         sub.add_option("--shards", a->shards, "number of shards to assign the sets to (1..100000)")
             ->check(CLI::Range(1, 100000))
             ->capture_default_str();
         return [a] { return run_plan(*a); };
     },
     "the deterministic work list: sets, sizes, action keys, shards"}};

}  // namespace
}  // namespace mf::cli
