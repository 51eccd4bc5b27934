// Validation rules: their thresholds and the configuration a preset's "validate" block or
// `--rules FILE` gives them.
//
// Conventions of this module (decided once here):
//  - a rule is named by its finding code (findings/findings.hpp), whose default severity, title
//    and docs anchor are findings/catalog.hpp's; a code never changes meaning;
//  - every threshold has a documented default and source (docs/rules.md; citations also at the
//    member below); `preset: "strict"` swaps in the stricter published numbers;
//  - suppressions remove findings of one code for materials whose name matches a glob
//    (`*`, `?`), as the Khronos glTF Validator's "ignore" list does for a whole run;
//  - configuration errors are returned as text (the CLI maps them to exit code 2), never thrown.
#pragma once
#include <map>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "findings/catalog.hpp"
#include "findings/findings.hpp"

namespace mf::rules {

// Numbers the rules compare against. Values are in the units named; "share" is a fraction of
// the pixels the rule looks at (0.05 = 5 %). Sources: docs/rules.md.
struct Thresholds {
    // ALBEDO_TOO_DARK / ALBEDO_TOO_BRIGHT: luminance of dielectric albedo, sRGB-encoded 0–255.
    // Substance (Allegorithmic) "The PBR Guide, Part 2" (2018), "Base color (dielectrics)":
    // no darker than 30 sRGB (tolerant) / 50 sRGB (strict), no brighter than 240 sRGB (tolerant)
    // / 243 sRGB (strict) — the bounds of Substance's "PBR Validate" node.
    double albedo_min_srgb = 30.0;
    double albedo_max_srgb = 240.0;
    // The share of the visible surface each may hold before it is worth a warning (matforge,
    // docs/rules.md "Where the numbers come from"). Dark: 18 %, calibrated on real downloads —
    // good sets hold ordinary crevices, grout and UV padding below 30 sRGB (corpus up to 3.6 %,
    // two good hand-named sets 6.6 % and 13.5 %), the sets a technical artist fixes 22.4 % and
    // up (Metal_Rusted_010; then 48.1, 51.0, 100 %). Bright: 5 % (good sets at most 0.01 %,
    // OfficeCeiling005 86 %).
    double albedo_dark_max_share = 0.18;
    double albedo_bright_max_share = 0.05;
    // METAL_ALBEDO_TOO_DARK: raw metals reflect 70–100 % → 180–255 sRGB (same guide,
    // "Metal reflectance values"). Measured F0 agrees: Real-Time Rendering 4th ed., Table 9.2
    // (after Hoffman 2015): the darkest common metal, titanium, has luminance ~188 sRGB.
    double metal_albedo_min_srgb = 180.0;
    double metal_albedo_max_share = 0.05;
    // Pixel classes for masked statistics. A metalness ≤ dielectric_max counts as dielectric,
    // ≥ metal_min as metal; values between are blends (rust, dirt) and are left out.
    double dielectric_max = 0.1;
    double metal_min = 0.9;
    double opacity_visible = 0.5;  // glTF 2.0 alphaCutoff default (§3.9.4)
    // METALNESS_NOT_BINARY: share of metalness strictly between the classes above.
    // The PBR Guide: metalness is "binary", grey only for transitions (oxidation, dirt).
    double metalness_max_intermediate_share = 0.10;
    // NOT_GRAYSCALE: largest |R−G|,|R−B|,|G−B| still "equal" (lossless / JPEG). JPEG's 4:2:0
    // chroma subsampling and YCbCr rounding move grey by a few codes (ITU-T T.81, JFIF 1.02).
    double grayscale_tolerance = 2.0 / 255.0;
    double grayscale_tolerance_jpeg = 6.0 / 255.0;
    double grayscale_max_share = 0.01;
    // CONSTANT_MAP: max − min at or below this (per channel) means "one value".
    double constant_tolerance = 1.0 / 255.0;
    double constant_tolerance_jpeg = 4.0 / 255.0;
    // OUT_OF_RANGE_VALUES: float inputs only; slack for half-float rounding (2^-10 at 1.0).
    double range_epsilon = 1e-3;
    double out_of_range_max_share = 0.0;
    // NONFINITE_VALUES: any NaN/Inf is reported (max share 0).
    double nonfinite_max_share = 0.0;
    // Normal maps, decoded n = 2c − 1. Every number below was set between the values measured
    // on real vendor maps (ambientCG, Poly Haven, 3dtextures.me; JPEG and WebP) and on maps that
    // are not tangent-space normals (height, roughness, occlusion, color photos, object-space,
    // gamma-encoded); docs/rules.md "Normal maps" lists both ranges.
    // NORMAL_NOT_UNIT_LENGTH (info): 8-bit quantization alone keeps |n| within ~0.01 of 1;
    // resized, blurred or lossy maps drift further and ingest renormalizes them.
    double normal_length_tolerance = 0.2;
    double normal_max_bad_length_share = 0.10;
    // NORMAL_INVALID (error): not a tangent-space normal map at all. A tangent map points away
    // from the surface: most vectors lie within 45° of +Z (real maps ≥ 73 %; photos, grey and
    // packed maps ≤ 5 %, object-space maps 3–25 %), its X and Y average near 0 (real |mean|
    // ≤ 0.13), it has no Z < −z_epsilon (real ≤ 0.3 %) and is never grey (R = G = B: real
    // ≤ 0.1 %, height/roughness/occlusion maps 100 %). Each map that is not a normal map fails
    // one of these by 1.5x or more.
    double normal_min_upward_share = 0.4;
    double normal_max_mean_xy = 0.25;
    double normal_z_epsilon = 0.02;
    double normal_max_negative_z_share = 0.05;
    double normal_max_gray_share = 0.5;
    // NORMAL_GAMMA_ENCODED (error): stored sRGB-encoded, so a flat vector (0.5, 0.5, 1) reads as
    // (0.74, 0.74, 1): both stored X/Y means above min_stored_mean_xy (real ≤ 0.13, encoded
    // ≥ 0.38), and decoded with the sRGB curve it passes NORMAL_INVALID's tests (X/Y means, upward
    // share, grey share) with a mean length within max_decoded_length_error of 1 (encoded copies
    // of real maps: ≤ 0.19; a grey height map decoded: 0.49).
    double normal_gamma_min_stored_mean_xy = 0.25;
    double normal_gamma_max_decoded_length_error = 0.3;
    // OPACITY_ALL_TRANSPARENT (error): more than max_share of the opacity (map, or the albedo's
    // alpha when it is the opacity) at or below invisible_max. Not the 0.5 cutoff: a blended
    // material of opacity 0.1–0.4 (glass, gauze) is visible. 0.02 holds JPEG noise around 0.
    double opacity_invisible_max = 0.02;
    double opacity_max_invisible_share = 0.999;
    // NORMAL_CONVENTION_MISMATCH / _UNKNOWN: confidence (0–1) a content verdict needs.
    double normal_convention_min_confidence = 0.6;

    bool operator==(const Thresholds&) const = default;
};

// The strict variant of the numbers above (PBR Guide strict bounds: 50–243 sRGB).
Thresholds strict_thresholds();

struct Suppression {
    std::string material = "*";  // glob over the material name
    std::string code;            // finding code, or "*"
    std::string reason;          // kept for the docs/audit; not printed in reports
    bool operator==(const Suppression&) const = default;
};

// A file the rules say is no map (an all-black placeholder a vendor ships, a stray export):
// discovery leaves it out, as an unrecognized file that says why.
struct Exclusion {
    std::string file;            // glob over the file's path in the set ('/'-separated) or its name
    std::string material = "*";  // glob over the material name
    std::string reason;          // said in the finding
    bool operator==(const Exclusion&) const = default;
};

struct RuleConfig {
    Thresholds thresholds;
    std::map<std::string, Severity, std::less<>> severity;  // overrides of the default severity
    std::vector<std::string> disabled;                      // codes never reported
    std::vector<Suppression> suppressions;
    std::vector<Exclusion> exclusions;

    // Two configurations are equal when every field is: what a memo of their results is keyed by
    // (plan/plan.hpp PlanShare), never a text made of them.
    bool operator==(const RuleConfig&) const = default;

    // The first exclusion that leaves `file` (relative to the set) of `material` out, or null.
    const Exclusion* excluded(std::string_view material, std::string_view file) const;

    // Effective severity of a code (override, else catalog default, else warning).
    Severity severity_of(std::string_view code) const;
    bool enabled(std::string_view code) const;
    bool suppressed(std::string_view material, std::string_view code) const;

    // Reads a config object over `base` (so a preset's block and then --rules FILE can be
    // layered). Accepted keys (docs/rules.md "Configuration"):
    //   "preset": "tolerant" | "strict"
    //   "rules": { CODE: "off" | "error"|"warning"|"info" | {"severity": ..., "enabled": bool,
    //              <threshold name>: number, ...} }
    //   "severityOverrides": { CODE: "error"|"warning"|"info" | 0..3 }   (glTF Validator style:
    //              0 error, 1 warning, 2 information, 3 hint → info)
    //   "ignore": [CODE, ...]                                            (glTF Validator style)
    //   "suppress": [ {"material": glob, "code": CODE|"*", "reason": text}, ... ]
    //   "exclude": [ glob | {"file": glob, "material": glob, "reason": text}, ... ]
    // Unknown keys, codes, threshold names or wrong types are errors (a typo must not silently
    // disable a check). Returns nullopt and sets `error` on failure.
    static std::optional<RuleConfig> from_json(const nlohmann::json& j, std::string& error,
                                               const RuleConfig& base = RuleConfig{});
};

// Every threshold by the names a rules file gives it ({CODE: {name: value}}): how a manifest
// records the run's (manifest::Manifest::thresholds), so a later reader (the report) judges as
// the run did. thresholds_from() reads such a table back over `base`; nullopt + `error` naming
// the entry when a code or name is unknown.
using ThresholdTable = std::map<std::string, std::map<std::string, double>>;
ThresholdTable threshold_table(const Thresholds& t);
std::optional<Thresholds> thresholds_from(const ThresholdTable& table, std::string& error,
                                          const Thresholds& base = Thresholds{});

// The defaults and threshold names per code, as JSON (for `matforge presets show` and docs).
nlohmann::json describe(const RuleConfig& cfg);

// Applies disabled codes, severity overrides and suppressions to a set's findings; protected
// codes (UNREADABLE_FILE, …) are never dropped nor lowered. Called once per set, over every
// stage's findings (plan/plan.hpp reported_findings). Returns how many were dropped.
int apply_config(std::vector<Finding>& findings, std::string_view material, const RuleConfig& cfg);

// Glob match with '*' and '?', case-sensitive.
bool glob_match(std::string_view pattern, std::string_view text);

}  // namespace mf::rules
