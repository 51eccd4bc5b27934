// plan_set: the front half of every command, decided once per material set. It discovers the
// files' roles, reads the chosen maps (falling back to the next candidate), routes every output
// role to its input (material/routing), runs every validation rule, judges the normal map's
// convention, and decides the set's size and what the preset must generate for missing roles.
// `ingest` = plan -> planes -> outputs -> manifest; `validate` = plan -> report. Every finding
// these stages raise comes from here (or from validate_set, which this calls), once, at its
// catalog severity; reported_findings() applies the rules config to them, once per set.
#pragma once
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "base/budget.hpp"
#include "findings/findings.hpp"
#include "findings/rules.hpp"
#include "image/image.hpp"
#include "manifest/manifest.hpp"
#include "material/discovery.hpp"
#include "material/provenance.hpp"
#include "material/routing.hpp"
#include "preset/preset.hpp"
#include "sets/sets.hpp"
#include "validate/validate.hpp"

namespace mf {

enum class PlanMode {
    decode,  // ingest: every chosen map decoded once, kept in memory for the planes
    stream,  // validate: headers only up front; the rules stream each map in bands
};

struct DecodedMap {
    Decoded img;  // 8-bit files stay codes until a step needs floats
    ImageInfo info;
};
// A decoded map is never changed once read: the plans of one set (ingest --preset a,b) and the
// planes made from it read the same pixels.
using SharedMap = std::shared_ptr<const DecodedMap>;

// What the plans of one set share (ingest --preset a,b and --tiers: one plan per preset and tier,
// on one worker, one after another). A file decodes to the same pixels whatever the preset and
// its max_size (a tier resamples the decoded map afterwards): the first plan that
// reads a file decodes it, later plans get the same map (or the same error), and the share lets
// go of it when the last of `plans` readers has it. The rules judge the same maps under the same
// rules config alike: validate_set runs once per distinct (maps, rules) pair. Thread-safe (a plan
// decodes its maps on up to two threads).
class PlanShare {
public:
    explicit PlanShare(int plans) : plans_(plans) {}
    // As read_image(in, out->img, out->info, error), from the share when `file` was read before.
    bool read(const InputFile& in, const std::string& file, SharedMap& out, std::string& error);
    // As validate::read_color_tag(in), from the share when `file`'s tag was read before: a PNG's
    // chunks are read once for every plan, as its pixels are.
    validate::ColorTagInfo color_tag(const InputFile& in, const std::string& file);
    // As validate::validate_set(maps, rules, vo), from the share when the same maps (role, file,
    // flags) were validated under the same rules before.
    validate::SetValidation validate(const std::vector<validate::MapInput>& maps, const rules::RuleConfig& rules,
                                     const validate::ValidateOptions& vo);

private:
    struct Entry {
        SharedMap map;                     // null when the read failed or the last reader has it
        int reads = 1;                     // plans that have read it
        bool gone = false;                 // every plan has read it: a further read decodes anew
        std::optional<std::string> error;  // why the read failed
    };
    // What validate_set judges a set by: the rules config and each map's role, file and flags.
    struct MapKey {
        Role role;
        std::string name, display;
        bool alternate;
        NormalConvention name_convention, engine_convention;
        std::vector<Role> unused;
        bool operator==(const MapKey&) const = default;
    };
    struct Validated {
        rules::RuleConfig rules;
        std::vector<MapKey> maps;
        validate::SetValidation result;
    };
    int plans_;
    std::mutex mutex_;
    std::map<std::string, Entry> entries_;
    std::map<std::string, validate::ColorTagInfo> tags_;  // by file
    std::vector<Validated> validated_;                    // one per distinct (rules, maps): a set's presets, a few
};

struct PlanOptions {
    const Preset* preset = nullptr;            // normal convention (override applied), sizes, needs
    const rules::RuleConfig* rules = nullptr;  // thresholds, severities, suppressions
    PlanMode mode = PlanMode::decode;
    MemoryBudget* budget = nullptr;  // decode mode: the set's decoded bytes are leased from it
    // Whether a core of the batch is idle now (a set alone, or the batch's tail; empty: never):
    // a second thread then joins the decoding whatever the set's size (sets of 64 MB and up
    // always decode on two).
    std::function<bool()> spare_core = {};
    // Decode mode: what an earlier plan of the same set decoded and validated (null: none).
    PlanShare* share = nullptr;
};

struct SetPlan {
    std::string convention;                       // naming family most maps follow
    std::map<Role, Candidate> inputs;             // input role -> the file that was read
    std::optional<Candidate> preview;             // the vendor's preview image (never read as a map)
    Provenance provenance;                        // vendor, asset id, licence (LICENCE_UNKNOWN when none)
    Routes routes;                                // output role -> where its values come from
    std::map<std::string, SharedMap> decoded;     // decode mode: by file
    std::optional<manifest::NormalFacts> normal;  // the routed normal map's convention verdict
    int width = 0, height = 0;                    // the set's output size (largest routed map, within max_size)
    std::vector<manifest::Constant> constants;    // generated for roles the outputs need
    std::vector<Finding> findings;                // in emission order; config applied
    bool normal_z_rebuilt = false;                // the normal map's blue is empty: Z from X and Y
    bool height_named_depth = false;              // read inverted for its name ("_depth"), no slopes to say
    bool partial = false;                         // some map could not be read
    std::optional<std::string> failure;           // nothing could be read: the set is an input failure
    uint64_t footprint = 0;                       // estimated decoded bytes (decode mode)
    std::unique_ptr<BudgetLease> lease;           // held until the plan is destroyed

    // The normal convention the outputs are converted from: the verdict, gl when undecided.
    NormalConvention normal_from() const;
};

SetPlan plan_set(const MaterialSource& src, const PlanOptions& opt);

// Discovery alone, as plan_set begins: each file's role by its name and the set's sidecars, one
// file chosen per role (headers read, no map decoded but where the pixels decide a name's role),
// and the findings discovery raises (AMBIGUOUS_MAP, UNRECOGNIZED_FILE with the rules'
// exclusions, the set's own NAMES_MERGED, …) as raised, the rules config not applied. For a
// caller that wants the roles without the rules' verdicts (the Python bindings' discover()).
SetDiscovery discover_roles(const MaterialSource& src, const Preset& preset, const rules::RuleConfig* rules);

// The set's findings as reported (the manifest entry, validate's reports): the plan's, with any
// ingest added while writing and encoding, and the rules config (disabled codes, severity
// overrides, suppressions) applied. Its one application: after every stage has raised its
// findings, so no stage decides on a finding the config would drop or lower.
std::vector<Finding> reported_findings(std::vector<Finding> findings, const std::string& material,
                                       const rules::RuleConfig& rules);

// The manifest entry's inputs of a plan (role order; the vendor's preview last, as role preview).
std::vector<manifest::Input> manifest_inputs(const SetPlan& plan);

// A set's manifest entry as its plan decides it, the one validate reports and ingest records
// (ingest adds its outputs, material files, archive, emissive strength and alpha): name,
// source, convention, status, inputs, constants, provenance, and the findings as reported under `rules`
// (reported_findings). Moves the plan's constants and findings out.
manifest::Material material_entry(SetPlan& plan, const std::string& name, std::string source,
                                  const rules::RuleConfig& rules);

}  // namespace mf
