#include "findings/rules.hpp"

#include <algorithm>
#include <cstdint>
#include <nlohmann/json.hpp>

namespace mf::rules {
namespace {

using Member = double Thresholds::*;
struct Param {
    std::string_view code;
    std::string_view name;  // key inside "rules": {CODE: {...}}
    Member member;
};

// Threshold names per code. A member shared by two codes (the share of ALBEDO_TOO_DARK and
// ALBEDO_TOO_BRIGHT) is one number: both rules look at the same dielectric pixels.
const std::vector<Param>& params() {
    static const std::vector<Param> p{
        {code::albedo_too_dark, "min_srgb", &Thresholds::albedo_min_srgb},
        {code::albedo_too_dark, "max_share", &Thresholds::albedo_dark_max_share},
        {code::albedo_too_dark, "dielectric_max", &Thresholds::dielectric_max},
        {code::albedo_too_dark, "opacity_visible", &Thresholds::opacity_visible},
        {code::albedo_too_bright, "max_srgb", &Thresholds::albedo_max_srgb},
        {code::albedo_too_bright, "max_share", &Thresholds::albedo_bright_max_share},
        {code::albedo_too_bright, "dielectric_max", &Thresholds::dielectric_max},
        {code::albedo_too_bright, "opacity_visible", &Thresholds::opacity_visible},
        {code::metal_albedo_too_dark, "min_srgb", &Thresholds::metal_albedo_min_srgb},
        {code::metal_albedo_too_dark, "max_share", &Thresholds::metal_albedo_max_share},
        {code::metal_albedo_too_dark, "metal_min", &Thresholds::metal_min},
        {code::metal_albedo_too_dark, "opacity_visible", &Thresholds::opacity_visible},
        {code::metalness_not_binary, "max_share", &Thresholds::metalness_max_intermediate_share},
        {code::metalness_not_binary, "dielectric_max", &Thresholds::dielectric_max},
        {code::metalness_not_binary, "metal_min", &Thresholds::metal_min},
        {code::not_grayscale, "tolerance", &Thresholds::grayscale_tolerance},
        {code::not_grayscale, "tolerance_jpeg", &Thresholds::grayscale_tolerance_jpeg},
        {code::not_grayscale, "max_share", &Thresholds::grayscale_max_share},
        {code::packed_channels_identical, "tolerance", &Thresholds::grayscale_tolerance},
        {code::packed_channels_identical, "tolerance_jpeg", &Thresholds::grayscale_tolerance_jpeg},
        {code::packed_channels_identical, "max_share", &Thresholds::grayscale_max_share},
        {code::constant_map, "tolerance", &Thresholds::constant_tolerance},
        {code::constant_map, "tolerance_jpeg", &Thresholds::constant_tolerance_jpeg},
        {code::out_of_range_values, "epsilon", &Thresholds::range_epsilon},
        {code::out_of_range_values, "max_share", &Thresholds::out_of_range_max_share},
        {code::nonfinite_values, "max_share", &Thresholds::nonfinite_max_share},
        {code::normal_not_unit_length, "length_tolerance", &Thresholds::normal_length_tolerance},
        {code::normal_not_unit_length, "max_bad_length_share", &Thresholds::normal_max_bad_length_share},
        {code::normal_invalid, "min_upward_share", &Thresholds::normal_min_upward_share},
        {code::normal_invalid, "max_mean_xy", &Thresholds::normal_max_mean_xy},
        {code::normal_invalid, "z_epsilon", &Thresholds::normal_z_epsilon},
        {code::normal_invalid, "max_negative_z_share", &Thresholds::normal_max_negative_z_share},
        {code::normal_invalid, "max_gray_share", &Thresholds::normal_max_gray_share},
        {code::normal_gamma_encoded, "min_stored_mean_xy", &Thresholds::normal_gamma_min_stored_mean_xy},
        {code::normal_gamma_encoded, "max_decoded_length_error", &Thresholds::normal_gamma_max_decoded_length_error},
        {code::opacity_all_transparent, "invisible_max", &Thresholds::opacity_invisible_max},
        {code::opacity_all_transparent, "max_share", &Thresholds::opacity_max_invisible_share},
        {code::normal_convention_mismatch, "min_confidence", &Thresholds::normal_convention_min_confidence},
        {code::normal_convention_unknown, "min_confidence", &Thresholds::normal_convention_min_confidence},
    };
    return p;
}

std::string json_number(double v) { return nlohmann::json(v).dump(); }

std::optional<Severity> parse_severity(const nlohmann::json& v) {
    if (v.is_string()) return severity_from_name(v.get<std::string>());
    if (v.is_number_integer()) {
        // glTF Validator severities: 0 error, 1 warning, 2 information, 3 hint.
        switch (v.get<std::int64_t>()) {  // never narrowed before the range is known
            case 0: return Severity::error;
            case 1: return Severity::warning;
            case 2:
            case 3: return Severity::info;
            default: break;
        }
    }
    return std::nullopt;
}

bool known_code(std::string_view c) { return find_code(c) != nullptr; }

// An input not read or an output not written is never a pass: no configuration switches these
// off, lowers them or suppresses them (a "*" suppression leaves them too).
// Inputs that fail (INPUT_NOT_FOUND, UNSAFE_PATH) are failures, never findings: no rule applies.
bool protected_code(std::string_view c) { return c == code::unreadable_file || c == code::output_write_failed; }
std::string protected_message(std::string_view c) {
    return "rules: " + std::string(c) +
           " cannot be switched off, lowered or suppressed: a file that was not read (or not written) always fails the run";
}

// Every threshold is a fraction in [0, 1] but the sRGB levels, in [0, 255].
std::pair<double, double> threshold_range(std::string_view name) {
    return name.find("srgb") != std::string_view::npos ? std::pair{0.0, 255.0} : std::pair{0.0, 1.0};
}

}  // namespace

Thresholds strict_thresholds() {
    Thresholds t;
    t.albedo_min_srgb = 50.0;   // PBR Guide part 2: strict lower bound
    t.albedo_max_srgb = 243.0;  // PBR Guide part 2: strict upper bound
    return t;
}

Severity RuleConfig::severity_of(std::string_view c) const {
    if (auto it = severity.find(c); it != severity.end()) return it->second;
    if (const CodeInfo* r = find_code(c)) return r->severity;
    return Severity::warning;
}

bool RuleConfig::enabled(std::string_view c) const {
    return std::find(disabled.begin(), disabled.end(), c) == disabled.end();
}

bool RuleConfig::suppressed(std::string_view material, std::string_view c) const {
    for (const auto& s : suppressions)
        if ((s.code == "*" || s.code == c) && glob_match(s.material, material)) return true;
    return false;
}

const Exclusion* RuleConfig::excluded(std::string_view material, std::string_view file) const {
    const auto slash = file.find_last_of('/');
    const std::string_view name = slash == std::string_view::npos ? file : file.substr(slash + 1);
    for (const auto& e : exclusions)
        if (glob_match(e.material, material) && (glob_match(e.file, file) || glob_match(e.file, name))) return &e;
    return nullptr;
}

bool glob_match(std::string_view p, std::string_view t) {
    // Iterative wildcard match with backtracking to the last '*': linear in practice.
    size_t pi = 0, ti = 0, star = std::string_view::npos, mark = 0;
    while (ti < t.size()) {
        if (pi < p.size() && (p[pi] == '?' || p[pi] == t[ti])) {
            ++pi;
            ++ti;
        } else if (pi < p.size() && p[pi] == '*') {
            star = pi++;
            mark = ti;
        } else if (star != std::string_view::npos) {
            pi = star + 1;
            ti = ++mark;
        } else {
            return false;
        }
    }
    while (pi < p.size() && p[pi] == '*') ++pi;
    return pi == p.size();
}

namespace {

// The stages of RuleConfig::from_json: each reads one key of the rules object into `cfg` and
// returns why it cannot (empty: read). Messages name the key and the code as a user wrote them.
using Json = nlohmann::json;

void disable(RuleConfig& cfg, const std::string& c) {
    if (cfg.enabled(c)) cfg.disabled.push_back(c);
}
void enable(RuleConfig& cfg, const std::string& c) { std::erase(cfg.disabled, c); }

// "preset": "strict" | "tolerant" resets the thresholds the rest of the object then adjusts.
std::string read_preset(const Json& p, RuleConfig& cfg) {
    if (p == "strict") cfg.thresholds = strict_thresholds();
    else if (p == "tolerant") cfg.thresholds = Thresholds{};
    else return "rules: \"preset\" must be \"tolerant\" or \"strict\"";
    return {};
}

// A protected code (an invisible material, a corrupt file) may only be raised to error or kept on.
std::string read_protected_rule(const std::string& c, const Json& rv) {
    bool raise_only = rv == "error" || rv == true || rv == "on" || rv.is_object();
    if (rv.is_object())
        for (const auto& [k, kv] : rv.items())
            raise_only = raise_only && ((k == "severity" && kv == "error") || (k == "enabled" && kv == true));
    return raise_only ? std::string() : protected_message(c);
}

// "rules".CODE.NAME = number: one threshold of the code, within its range.
std::string read_threshold(const std::string& c, const std::string& name, const Json& v, RuleConfig& cfg) {
    const auto it = std::find_if(params().begin(), params().end(),
                                 [&](const Param& p) { return p.code == c && p.name == name; });
    if (it == params().end()) return "rules: \"" + c + "\" has no threshold \"" + name + "\"";
    const auto [lo, hi] = threshold_range(name);
    if (!v.is_number() || !(v.get<double>() >= lo && v.get<double>() <= hi))
        return "rules: \"" + c + "\"." + name + " must be a number within " + json_number(lo) + ".." + json_number(hi);
    cfg.thresholds.*(it->member) = v.get<double>();
    return {};
}

// "rules".CODE: "off" | "on" | true | false | a severity | {"severity", "enabled", thresholds...}.
std::string read_rule(const std::string& c, const Json& rv, RuleConfig& cfg) {
    if (protected_code(c)) return read_protected_rule(c, rv);
    if (!known_code(c)) return "rules: unknown finding code \"" + c + "\"";
    std::string expected = "rules: \"" + c + "\": expected \"off\", a severity or an object";
    if (rv.is_string() || rv.is_boolean()) {
        if (rv == "off" || rv == false) disable(cfg, c);
        else if (rv == true || rv == "on") enable(cfg, c);
        else if (auto s = parse_severity(rv)) {
            cfg.severity[c] = *s;
            enable(cfg, c);
        } else {
            return expected;
        }
        return {};
    }
    if (!rv.is_object()) return expected;
    for (const auto& [name, v] : rv.items()) {
        if (name == "severity") {
            const auto s = parse_severity(v);
            if (!s) return "rules: \"" + c + "\".severity must be error, warning or info";
            cfg.severity[c] = *s;
        } else if (name == "enabled") {
            if (!v.is_boolean()) return "rules: \"" + c + "\".enabled must be true or false";
            if (v.get<bool>()) enable(cfg, c);
            else disable(cfg, c);
        } else if (std::string why = read_threshold(c, name, v, cfg); !why.empty()) {
            return why;
        }
    }
    return {};
}

std::string read_rules(const Json& val, RuleConfig& cfg) {
    if (!val.is_object()) return "rules: \"rules\" must be an object keyed by finding code";
    for (const auto& [c, rv] : val.items())
        if (std::string why = read_rule(c, rv, cfg); !why.empty()) return why;
    return {};
}

// "severityOverrides": {CODE: severity} (the older spelling of "rules").
std::string read_severity_overrides(const Json& val, RuleConfig& cfg) {
    if (!val.is_object()) return "rules: \"severityOverrides\" must be an object";
    for (const auto& [c, v] : val.items()) {
        const auto s = parse_severity(v);
        if (protected_code(c)) {
            if (s != Severity::error) return protected_message(c);
            continue;
        }
        if (!known_code(c) || !s) return "rules: bad severityOverrides entry \"" + c + "\"";
        cfg.severity[c] = *s;
    }
    return {};
}

// "ignore": [CODE, ...] switched off.
std::string read_ignore(const Json& val, RuleConfig& cfg) {
    if (!val.is_array()) return "rules: \"ignore\" must be an array of finding codes";
    for (const auto& v : val) {
        if (v.is_string() && protected_code(v.get<std::string>())) return protected_message(v.get<std::string>());
        if (!v.is_string() || !known_code(v.get<std::string>()))
            return "rules: \"ignore\" holds an unknown finding code";
        disable(cfg, v.get<std::string>());
    }
    return {};
}

// One "suppress" entry: {"code": CODE or "*", "material": glob, "reason": text}.
std::string read_suppression(const Json& v, Suppression& s) {
    if (!v.is_object() || !v.contains("code") || !v.at("code").is_string())
        return "rules: each \"suppress\" entry needs a \"code\"";
    s.code = v.at("code").get<std::string>();
    if (protected_code(s.code)) return protected_message(s.code);
    if (s.code != "*" && !known_code(s.code))
        return "rules: \"suppress\" names unknown finding code \"" + s.code + "\"";
    if (v.contains("material")) {
        if (!v.at("material").is_string()) return "rules: \"suppress\".material must be a string (glob)";
        s.material = v.at("material").get<std::string>();
    }
    if (v.contains("reason") && v.at("reason").is_string()) s.reason = v.at("reason").get<std::string>();
    for (const auto& item : v.items())
        if (item.key() != "code" && item.key() != "material" && item.key() != "reason")
            return "rules: unknown key \"" + item.key() + "\" in a \"suppress\" entry";
    return {};
}

std::string read_suppress(const Json& val, RuleConfig& cfg) {
    if (!val.is_array()) return "rules: \"suppress\" must be an array";
    for (const auto& v : val) {
        Suppression s;
        if (std::string why = read_suppression(v, s); !why.empty()) return why;
        cfg.suppressions.push_back(std::move(s));
    }
    return {};
}

// "exclude": [glob | {"file": glob, "material": glob, "reason": text}, ...].
std::string read_exclude(const Json& val, RuleConfig& cfg) {
    if (!val.is_array()) return "rules: \"exclude\" must be an array of file globs or objects";
    for (const auto& v : val) {
        Exclusion e;
        if (v.is_string()) {
            e.file = v.get<std::string>();
        } else if (v.is_object() && v.contains("file") && v.at("file").is_string()) {
            e.file = v.at("file").get<std::string>();
            for (const auto& item : v.items()) {
                const std::string& k = item.key();
                if (k == "file") continue;
                if ((k != "material" && k != "reason") || !item.value().is_string())
                    return "rules: an \"exclude\" entry takes \"file\", \"material\" and \"reason\" (strings), "
                           "not \"" +
                           k + "\"";
                (k == "material" ? e.material : e.reason) = item.value().get<std::string>();
            }
        } else {
            return "rules: each \"exclude\" entry is a file glob or an object with a \"file\" glob";
        }
        if (e.file.empty()) return "rules: an \"exclude\" file glob is empty";
        cfg.exclusions.push_back(std::move(e));
    }
    return {};
}

// Bounds that contradict each other would make a rule fire on everything or on nothing.
std::string check_bounds(const Thresholds& t) {
    if (t.albedo_min_srgb > t.albedo_max_srgb)
        return "rules: ALBEDO_TOO_DARK.min_srgb (" + json_number(t.albedo_min_srgb) +
               ") is above ALBEDO_TOO_BRIGHT.max_srgb (" + json_number(t.albedo_max_srgb) + ")";
    if (t.dielectric_max > t.metal_min)
        return "rules: dielectric_max (" + json_number(t.dielectric_max) + ") is above metal_min (" +
               json_number(t.metal_min) + ")";
    return {};
}

}  // namespace

std::optional<RuleConfig> RuleConfig::from_json(const nlohmann::json& j, std::string& error, const RuleConfig& base) {
    if (!j.is_object()) {
        error = "rules configuration must be a JSON object";
        return std::nullopt;
    }
    RuleConfig cfg = base;
    // "preset" first: it resets the thresholds the rest of the object then adjusts.
    error = j.contains("preset") ? read_preset(j.at("preset"), cfg) : std::string();
    for (auto it = j.begin(); error.empty() && it != j.end(); ++it) {
        const std::string& key = it.key();
        if (key == "preset" || key == "$comment" || key == "description") continue;
        if (key == "rules") error = read_rules(*it, cfg);
        else if (key == "severityOverrides") error = read_severity_overrides(*it, cfg);
        else if (key == "ignore") error = read_ignore(*it, cfg);
        else if (key == "suppress") error = read_suppress(*it, cfg);
        else if (key == "exclude") error = read_exclude(*it, cfg);
        else error = "rules: unknown key \"" + key + "\"";
    }
    if (error.empty()) error = check_bounds(cfg.thresholds);
    if (!error.empty()) return std::nullopt;
    return cfg;
}

ThresholdTable threshold_table(const Thresholds& t) {
    ThresholdTable table;
    for (const auto& p : params()) table[std::string(p.code)][std::string(p.name)] = t.*(p.member);
    return table;
}

std::optional<Thresholds> thresholds_from(const ThresholdTable& table, std::string& error, const Thresholds& base) {
    Thresholds t = base;
    for (const auto& entry : table)
        for (const auto& [name, value] : entry.second) {
            const std::string& code = entry.first;
            const std::string& key = name;  // clang 14 captures no structured binding
            const auto it = std::find_if(params().begin(), params().end(),
                                         [&](const Param& p) { return p.code == code && p.name == key; });
            if (it == params().end()) {
                error = "thresholds: " + code + " has no threshold '" + key + "'";
                return std::nullopt;
            }
            t.*(it->member) = value;
        }
    return t;
}

nlohmann::json describe(const RuleConfig& cfg) {
    nlohmann::json rules = nlohmann::json::object();
    for (const auto& r : finding_catalog()) {
        nlohmann::json e;
        e["severity"] = severity_name(cfg.severity_of(r.code));
        e["enabled"] = cfg.enabled(r.code);
        for (const auto& p : params())
            if (p.code == r.code) e[std::string(p.name)] = cfg.thresholds.*(p.member);
        rules[std::string(r.code)] = e;
    }
    nlohmann::json sup = nlohmann::json::array();
    for (const auto& s : cfg.suppressions)
        sup.push_back({{"material", s.material}, {"code", s.code}, {"reason", s.reason}});
    nlohmann::json out{{"rules", rules}, {"suppress", sup}};
    // Only when there are any: the digest of a run without exclusions (cache keys) is unchanged.
    for (const auto& e : cfg.exclusions)
        out["exclude"].push_back({{"file", e.file}, {"material", e.material}, {"reason", e.reason}});
    return out;
}

int apply_config(std::vector<Finding>& findings, std::string_view material, const RuleConfig& cfg) {
    int removed = 0;
    std::vector<Finding> kept;
    kept.reserve(findings.size());
    for (auto& f : findings) {
        if (protected_code(f.code)) {  // never removed nor lowered (from_json refuses to; "*" too)
            kept.push_back(std::move(f));
            continue;
        }
        if (!cfg.enabled(f.code) || cfg.suppressed(material, f.code)) {
            ++removed;
            continue;
        }
        if (auto it = cfg.severity.find(f.code); it != cfg.severity.end()) f.severity = it->second;
        kept.push_back(std::move(f));
    }
    findings = std::move(kept);
    return removed;
}

}  // namespace mf::rules
