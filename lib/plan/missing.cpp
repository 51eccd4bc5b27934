#include "plan/missing.hpp"

#include <algorithm>
#include <cstdio>
#include <optional>

#include "findings/catalog.hpp"

namespace mf {
namespace {
std::string format_number(float v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", static_cast<double>(v));
    return buf;
}
}  // namespace

std::set<Role> written_roles(const Preset& preset, const std::set<Role>& available) {
    std::set<Role> roles;
    for (const auto& o : preset.outputs) {
        const auto used = o.roles();
        const bool any = std::any_of(used.begin(), used.end(), [&](Role r) { return available.count(r) > 0; });
        if (!o.always && !any) continue;
        for (const auto& c : o.channels) {
            if (c.kind != ChannelSpec::Kind::role && c.kind != ChannelSpec::Kind::smoothness) continue;
            if (c.optional && !available.count(c.role)) continue;
            roles.insert(c.role);
        }
    }
    return roles;
}

std::vector<Finding> missing_map_findings(const Preset& preset, const std::set<Role>& available,
                                          const std::set<Role>& written, std::vector<manifest::Constant>& constants,
                                          bool generated) {
    std::vector<Finding> findings;
    const std::string verb = generated ? "generated" : "ingest generates";
    for (int ri = 0; ri < kOutputRoleCount; ++ri) {
        const Role r = static_cast<Role>(ri);
        if (available.count(r)) continue;
        const std::string rname(role_name(r));
        std::string what;
        std::optional<manifest::Constant> made;
        if (written.count(r)) {
            if (r == Role::albedo) {
                const auto& a = preset.default_albedo;
                made = manifest::Constant{r, {a[0], a[1], a[2]}};
                what = verb + " constant albedo (linear " + format_number(a[0]) + ", " + format_number(a[1]) + ", " +
                       format_number(a[2]) + ")";
            } else if (r == Role::normal || r == Role::emissive) {
                made = manifest::Constant{r, r == Role::normal ? std::vector<float>{0.f, 0.f, 1.f}
                                                               : std::vector<float>{0.f, 0.f, 0.f}};
                what = verb + (r == Role::normal ? " a flat normal" : " black emission");
            } else {
                const float v = preset.default_value(r);
                made = manifest::Constant{r, {v}};
                what = verb + " constant " + format_number(v);
                if (r == Role::metalness) what += v == 0.f ? " (dielectric)" : " (metal)";
            }
            constants.push_back(*made);
        } else {
            what = "nothing written for it";
        }
        const auto sev = preset.missing_severity.find(r);
        if (sev == preset.missing_severity.end()) continue;
        Figures figures;
        if (made) figures["generated"] = made->value.size() == 1 ? Figure(made->value[0]) : Figure(made->value);
        Finding f = finding(code::missing_map, rname, "", "no " + rname + " map; " + what, std::move(figures));
        f.severity = sev->second;  // the preset's missing_severity decides (docs/interface.md "Finding codes")
        findings.push_back(std::move(f));
    }
    return findings;
}

}  // namespace mf
