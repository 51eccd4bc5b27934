// matforge plan <input>... -o plan.json [--preset NAME|FILE] [--rules FILE] [--shards N]
//                [--commands --out-dir DIR] [--changed-since MANIFEST]
// The deterministic work list: every set with its size, its action key and, with --shards, the
// shard `ingest --shard I/N` gives it. Reads every input file once (to hash it), decodes nothing.
// --commands: one shell command per shard on standard output, one a line (the exact
// `matforge ingest ... --shard I/N`, absolute paths, POSIX-quoted), for any farm that takes a
// command per task (cuecmd, Deadline, GNU parallel, xargs -P, a Kubernetes Indexed Job).
// --changed-since: only the sets whose action key differs from (or is absent in) an earlier
// run's manifest, each with its shard in the whole library's split; --commands then prints only
// the shards that hold one.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <set>

#include "command.hpp"
#include "core/files.hpp"
#include "core/json.hpp"
#include "core/text.hpp"
#include "core/version.hpp"
#include "manifest/manifest.hpp"
#include "preset/preset.hpp"
#include "process/batch.hpp"
#include "process/validate_batch.hpp"
#include "process/work.hpp"
#include "sets/sets.hpp"

namespace mf::cli {
namespace {

struct PlanArgs {
    std::vector<std::string> inputs;
    std::string out, preset = "gltf", rules_file;
    int shards = 1;
    bool commands = false;
    std::string out_dir;        // with --commands: the folder the shards' ingests write
    std::string changed_since;  // an earlier run's manifest.json
};

// `s` as one word of a POSIX shell command line: as it is when it holds only characters no
// shell treats specially, else in single quotes (a ' inside as '\'').
std::string shell_word(const std::string& s) {
    const bool plain = !s.empty() && s.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                         "0123456789_-./:=+,@%") == std::string::npos;
    if (plain) return s;
    std::string out = "'";
    for (const char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

std::string absolute(const std::string& p) {
    std::error_code ec;
    const auto a = std::filesystem::absolute(p, ec);
    return ec ? p : a.lexically_normal().generic_string();
}

// This binary's absolute path ("" when /proc cannot say).
std::string self_path() {
    std::error_code ec;
    const auto self = std::filesystem::read_symlink("/proc/self/exe", ec);
    return ec ? std::string() : self.string();
}

// This binary as the commands name it (a farm's node runs the same one on the shared file system).
std::string self_binary() {
    const std::string self = self_path();
    return shell_word(self.empty() ? std::string("matforge") : self);
}

// The preset as the shards must name it: a shipped name as it is (load_preset takes a shipped
// name before a file of that name in the working folder), a file by its absolute path.
std::string preset_word(const std::string& preset) { return shipped_preset_text(preset) ? preset : absolute(preset); }

// The ingest command of shard I of N: this binary, the inputs, the output folder, the preset
// and rules, as plan was given them.
std::string shard_command(const PlanArgs& a, int index) {
    std::string line = self_binary() + " ingest";
    for (const auto& in : a.inputs) line += " " + shell_word(absolute(in));
    line += " -o " + shell_word(absolute(a.out_dir));
    line += " --preset " + shell_word(preset_word(a.preset));
    if (!a.rules_file.empty()) line += " --rules " + shell_word(absolute(a.rules_file));
    return line + " --shard " + std::to_string(index) + "/" + std::to_string(a.shards);
}

// Why the commands cannot be printed one a line: a path with a control character (a newline
// above all). Every runner of a command list (xargs -d '\n', GNU parallel, cuecmd, a
// `while read` loop) splits lines before any shell sees the quotes, so a folder named
// "lib<newline>touch X<newline>x" would run `touch X` as a command of its own. Empty: none.
std::string line_breaking_path(const PlanArgs& a) {
    std::vector<std::pair<std::string, std::string>> words{{"the output folder", absolute(a.out_dir)},
                                                           {"the preset", preset_word(a.preset)}};
    for (const auto& in : a.inputs) words.emplace_back("the input", absolute(in));
    if (!a.rules_file.empty()) words.emplace_back("the rules file", absolute(a.rules_file));
    if (const std::string self = self_path(); !self.empty()) words.emplace_back("this binary's path", self);
    for (const auto& [what, w] : words)
        for (const char c : w)
            if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
                char code[8];
                std::snprintf(code, sizeof code, "0x%02x", static_cast<unsigned>(static_cast<unsigned char>(c)));
                return what + " \"" + terminal_safe(w) + "\" holds a control character (byte " + code +
                       (c == '\n' ? ", a newline" : "") +
                       "): a runner of one command a line would split the command there and run the rest as "
                       "commands of their own; rename it, or run `matforge ingest ... --shard I/N` yourself";
            }
    return {};
}

ExitCode run_plan(const PlanArgs& a) {
    if (std::string why = no_usable_input({a.inputs.begin(), a.inputs.end()}); !why.empty()) return fail("plan", why);
    if (a.commands)
        if (std::string why = line_breaking_path(a); !why.empty()) return fail("plan", "--commands: " + why);
    std::string error;
    auto preset = load_preset(a.preset, error);
    if (!preset) return fail("plan", error);
    // An action key is one max_size's (the resolved preset's): a list of tiers has one per tier.
    if (!preset->tiers.empty())
        return fail("plan", a.preset + ": max_size is a list of tiers; a plan's action keys are those of one "
                                       "max_size: plan each tier with a preset file of that max_size");
    auto rules = load_rule_config(*preset, a.rules_file, error);
    if (!rules) return fail("plan", error);
    auto color = ColorContext::create(error);
    if (!color) return fail("plan", error);
    // The earlier run's keys, by material name (read one material at a time).
    std::map<std::string, std::string> earlier;
    if (!a.changed_since.empty() && !manifest::read_manifest(
                                        a.changed_since,
                                        [&](manifest::Material&& m, std::string&) {
                                            earlier[m.name] = m.key;
                                            return true;
                                        },
                                        error))
        return fail("plan", "--changed-since: " + error);
    const std::vector<std::filesystem::path> inputs(a.inputs.begin(), a.inputs.end());
    const Batch batch = Batch::find(inputs);
    for (const std::string& n : batch.skipped) say("plan", "note: " + n);
    if (std::string why = written_file_conflict(a.out, inputs, batch.sets); !why.empty())
        return fail("plan", "-o " + why);
    Plan plan = Plan::of(batch, preset->name, context_digest(*preset, *rules, *color), a.shards,
                         a.changed_since.empty() ? nullptr : &earlier);
    if (!a.changed_since.empty()) plan.changed_since = a.changed_since;
    std::set<int> to_run;  // shards holding a listed set
    for (const Plan::Set& s : plan.sets) to_run.insert(s.shard);
    const nlohmann::json out = plan.to_json();
    const std::string text = json_text(out);
    if (!write_file_atomic(a.out, std::span(reinterpret_cast<const unsigned char*>(text.data()), text.size()), error))
        return fail("plan", error, ExitCode::findings);
    if (a.commands) {
        for (int i = 0; i < a.shards; ++i)
            if (a.changed_since.empty() || to_run.count(i)) std::cout << shard_command(a, i) << '\n';
        std::cout.flush();
        say("plan", "then, when every shard is done: " + self_binary() + " merge " +
                        shell_word(absolute(a.out_dir) + "/manifest.shard-") + "*" +
                        shell_word("-of-" + std::to_string(a.shards) + ".json") + " -o " +
                        shell_word(absolute(a.out_dir) + "/manifest.json"));
    }
    return plan.unreadable() ? ExitCode::findings : ExitCode::ok;
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
         auto* out_dir = sub.add_option("--out-dir", a->out_dir, "with --commands: the output folder of the ingests");
         auto* commands = sub.add_flag(
             "--commands", a->commands,
             "print one `matforge ingest ... --shard I/N` command per shard on standard output, one a line");
         commands->needs(out_dir);
         out_dir->needs(commands);
         sub.add_option("--changed-since", a->changed_since,
                        "an earlier run's manifest.json: list only the sets whose action key differs or is new")
             ->check(CLI::ExistingFile);
         return [a] { return run_plan(*a); };
     },
     "the deterministic work list: sets, sizes, action keys, shards"}};

}  // namespace
}  // namespace mf::cli
