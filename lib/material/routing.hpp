// Routing: which input map feeds each output role. Decided here and nowhere else: the set
// planner (lib/plan) and the validator (lib/validate) both call route_roles(), so ingest
// and validate always judge the same maps.
//
// Preference, for every output role: its dedicated map, then a packed input holding it (orm,
// metallic_roughness, ort, the engines' packings — see packed_layout(); a smoothness channel is
// read inverted), then gloss (inverted) for roughness; opacity
// with no map of its own comes from the albedo's alpha (glTF 2.0 §3.9.2: baseColor's alpha is
// the coverage). A packed input feeds a role only when it has that channel.
#pragma once
#include <functional>
#include <map>
#include <optional>
#include <vector>

#include "material/roles.hpp"

namespace mf {

struct Route {
    Role from = Role::albedo;  // the input role whose map holds the values
    int channel = -1;          // -1: the whole map; 0..3: one channel of it
    bool invert = false;       // gloss or a smoothness channel -> roughness (1 - v)
    bool from_alpha = false;   // opacity carried in the albedo's last channel
};
using Routes = std::map<Role, Route>;  // output role -> its route

// Every route an output role may take, best first (a dedicated map, packed inputs, gloss).
// The albedo-alpha route of opacity is not listed: it depends on the albedo's channels.
std::vector<Route> route_candidates(Role out);

// The route of `out` (any role a packed input can hold, translucency included), nullopt when
// none of its candidates can be read; `channels` as below.
// `unused(out, from)`: the input of role `from` must not feed `out` (a glTF material whose
// metallicFactor is 0 does not use its texture's metalness channel).
using Unused = std::function<bool(Role out, Role from)>;
std::optional<Route> route_of(Role out, const std::function<int(Role)>& channels, const Unused& unused = {});

// The route of every output role that has one. `channels(r)` is the channel count of the input
// of role r that can be read, 0 when there is none. `albedo_alpha`: whether an albedo with an
// alpha channel (grey+alpha or RGBA: 2 or 4 channels) provides opacity when no opacity map exists.
Routes route_roles(const std::function<int(Role)>& channels, bool albedo_alpha = true, const Unused& unused = {});

}  // namespace mf
