// Small helpers for the discovery tests that came with the naming-gap, sidecar and corpus tests.
#pragma once
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "material/discovery.hpp"

namespace mf::discovery_test {

using HeaderMap = std::map<std::string, HeaderInfo>;

inline std::function<std::optional<HeaderInfo>(const std::string&)> headers(HeaderMap m) {
    return [m = std::move(m)](const std::string& f) -> std::optional<HeaderInfo> {
        const auto it = m.find(f);
        if (it == m.end()) return std::nullopt;
        return it->second;
    };
}

inline HeaderInfo square(int size, int channels = 3, int depth = 8) {
    HeaderInfo h;
    h.width = h.height = size;
    h.channels = channels;
    h.bit_depth = depth;
    return h;
}

inline const RoleChoice* find_choice(const SetDiscovery& d, Role r) {
    for (const auto& c : d.choices)
        if (c.role == r) return &c;
    return nullptr;
}

inline std::string chosen_file(const SetDiscovery& d, Role r) {
    const auto* c = find_choice(d, r);
    return c ? c->chosen.file : std::string("<none>");
}

// Every candidate file of a role, chosen first.
inline std::vector<std::string> candidates(const SetDiscovery& d, Role r) {
    std::vector<std::string> out;
    if (const auto* c = find_choice(d, r)) {
        out.push_back(c->chosen.file);
        for (const auto& x : c->rejected) out.push_back(x.file);
    }
    return out;
}

inline std::vector<std::string> roles_of(const SetDiscovery& d) {
    std::vector<std::string> out;
    for (const auto& c : d.choices) out.emplace_back(role_name(c.role));
    return out;
}

// "CODE role file" per finding, in order.
inline std::vector<std::string> keys(const SetDiscovery& d) {
    std::vector<std::string> out;
    for (const auto& f : d.findings) out.push_back(f.code + " " + f.role + " " + f.file);
    return out;
}

// The UNRECOGNIZED_FILE reason given for `file`, "" when there is none.
inline std::string unrecognized_reason(const SetDiscovery& d, const std::string& file) {
    for (const auto& f : d.findings)
        if (f.code == code::unrecognized_file && f.file == file)
            return mf::figure_string(f.figures, "reason").value_or("?");
    return "";
}

inline const Finding* find_finding(const SetDiscovery& d, std::string_view code, std::string_view role) {
    for (const auto& f : d.findings)
        if (f.code == code && f.role == role) return &f;
    return nullptr;
}

}  // namespace mf::discovery_test
