#include "material/roles.hpp"

#include <stdexcept>

namespace mf {
namespace {
//                                 role, name, output, color, channels, packed
constexpr std::array<RoleTraits, kRoleCount> kTraits{{
    {Role::albedo, "albedo", true, true, 3, false},
    {Role::normal, "normal", true, false, 3, false},
    {Role::roughness, "roughness", true, false, 1, false},
    {Role::metalness, "metalness", true, false, 1, false},
    {Role::occlusion, "occlusion", true, false, 1, false},
    {Role::height, "height", true, false, 1, false},
    {Role::emissive, "emissive", true, true, 3, false},
    {Role::opacity, "opacity", true, false, 1, false},
    {Role::gloss, "gloss", false, false, 1, false},
    {Role::specular, "specular", false, false, 3, false},
    {Role::orm, "orm", false, false, 3, true},
    {Role::metallic_roughness, "metallic_roughness", false, false, 3, true},
    {Role::ort, "ort", false, false, 3, true},
    {Role::cavity, "cavity", false, false, 1, false},
    {Role::translucency, "translucency", false, false, 1, false},
}};
}  // namespace

const RoleTraits& traits(Role r) { return kTraits.at(static_cast<size_t>(r)); }
std::string_view role_name(Role r) { return traits(r).name; }

std::optional<Role> role_from_name(std::string_view name) {
    for (const auto& t : kTraits)
        if (t.name == name) return t.role;
    if (name == "arm") return Role::orm;
    return std::nullopt;
}

std::string_view convention_name(NormalConvention c) {
    switch (c) {
        case NormalConvention::gl: return "gl";
        case NormalConvention::dx: return "dx";
        case NormalConvention::unknown: break;
    }
    return "unknown";
}

std::optional<NormalConvention> convention_from_name(std::string_view name) {
    if (name == "gl") return NormalConvention::gl;
    if (name == "dx") return NormalConvention::dx;
    if (name == "unknown") return NormalConvention::unknown;
    return std::nullopt;
}

std::array<std::optional<Role>, 3> packed_layout(Role packed) {
    switch (packed) {
        case Role::orm: return {Role::occlusion, Role::roughness, Role::metalness};
        // glTF 2.0 §3.9.2: metallicRoughnessTexture, G = roughness, B = metalness, R ignored.
        case Role::metallic_roughness: return {std::nullopt, Role::roughness, Role::metalness};
        // Megascans ORT: B is translucency, which is not metalness.
        case Role::ort: return {Role::occlusion, Role::roughness, Role::translucency};
        default: break;
    }
    return {std::nullopt, std::nullopt, std::nullopt};
}

}  // namespace mf
