#include "material/routing.hpp"

namespace mf {

std::vector<Route> route_candidates(Role out) {
    std::vector<Route> list{{out, -1, false, false}};
    for (const Role packed : packed_roles()) {
        const auto layout = packed_layout(packed);
        for (int ch = 0; ch < 4; ++ch)
            if (const auto& c = layout[static_cast<size_t>(ch)]; c && c->role == out)
                list.push_back({packed, ch, c->invert, false});
    }
    if (out == Role::roughness) list.push_back({Role::gloss, -1, true, false});
    return list;
}

std::optional<Route> route_of(Role out, const std::function<int(Role)>& channels, const Unused& unused) {
    for (const Route& r : route_candidates(out)) {
        const int n = channels(r.from);
        if (n > 0 && n > r.channel && !(unused && unused(out, r.from))) return r;
    }
    return std::nullopt;
}

Routes route_roles(const std::function<int(Role)>& channels, bool albedo_alpha, const Unused& unused) {
    Routes routes;
    for (int ri = 0; ri < kOutputRoleCount; ++ri)
        if (const auto r = route_of(static_cast<Role>(ri), channels, unused)) routes.emplace(static_cast<Role>(ri), *r);
    if (albedo_alpha && !routes.count(Role::opacity)) {
        const auto albedo = routes.find(Role::albedo);
        const int n = albedo != routes.end() && albedo->second.from == Role::albedo ? channels(Role::albedo) : 0;
        if (n == 2 || n == 4) routes.emplace(Role::opacity, Route{Role::albedo, n - 1, false, true});
    }
    return routes;
}

}  // namespace mf
