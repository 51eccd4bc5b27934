#include "process/missing.hpp"

#include <cstdio>

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
                                          const std::set<Role>& written, nlohmann::json& constants) {
    std::vector<Finding> findings;
    for (int ri = 0; ri < kOutputRoleCount; ++ri) {
        const Role r = static_cast<Role>(ri);
        if (available.count(r)) continue;
        const std::string rname(role_name(r));
        std::string what;
        if (written.count(r)) {
            if (r == Role::albedo) {
                const auto& a = preset.default_albedo;
                constants[rname] = a;
                what = "generated constant albedo (linear " + format_number(a[0]) + ", " + format_number(a[1]) + ", " +
                       format_number(a[2]) + ")";
            } else if (r == Role::normal || r == Role::emissive) {
                constants[rname] = r == Role::normal ? nlohmann::json{0, 0, 1} : nlohmann::json{0, 0, 0};
                what = r == Role::normal ? "generated a flat normal" : "generated black emission";
            } else {
                const float v = preset.default_value(r);
                constants[rname] = v;
                what = "generated constant " + format_number(v);
                if (r == Role::metalness) what += v == 0.f ? " (dielectric)" : " (metal)";
            }
        } else {
            what = "nothing written for it";
        }
        const auto sev = preset.missing_severity.find(r);
        if (sev == preset.missing_severity.end()) continue;
        findings.push_back({std::string(code::missing_map), sev->second, rname, "", "no " + rname + " map; " + what,
                            constants.contains(rname) ? nlohmann::json{{"generated", constants[rname]}}
                                                      : nlohmann::json::object()});
    }
    return findings;
}

}  // namespace mf
