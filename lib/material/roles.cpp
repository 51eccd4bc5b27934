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
    // Megascans' and Poly Haven's translucency maps are colour (the light let through: leaves
    // green, paper orange; Unity's import of them is sRGB); ORT's B channel reads it as one value.
    {Role::translucency, "translucency", false, true, 3, false},
    {Role::metallic_smoothness, "metallic_smoothness", false, false, 4, true},
    {Role::mask_map, "mask_map", false, false, 4, true},
    {Role::specular_smoothness, "specular_smoothness", false, false, 4, true},
    {Role::mra, "mra", false, false, 3, true},
    {Role::rma, "rma", false, false, 3, true},
    {Role::rm, "rm", false, false, 2, true},
    {Role::preview, "preview", false, true, 4, false},
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

PackedLayout packed_layout(Role packed) {
    using R = Role;
    constexpr PackedChannel occ{R::occlusion}, rough{R::roughness}, metal{R::metalness};
    constexpr PackedChannel smooth{R::roughness, true};
    switch (packed) {
        case R::orm: return {occ, rough, metal, std::nullopt};
        // glTF 2.0 §3.9.2: metallicRoughnessTexture, G = roughness, B = metalness, R ignored.
        case R::metallic_roughness: return {std::nullopt, rough, metal, std::nullopt};
        // Megascans ORT: B is translucency, which is not metalness.
        case R::ort: return {occ, rough, PackedChannel{R::translucency}, std::nullopt};
        // Unity's Standard/URP shader: _MetallicGlossMap R = metallic, A = smoothness.
        case R::metallic_smoothness: return {metal, std::nullopt, std::nullopt, smooth};
        // HDRP Lit's _MaskMap: R metallic, G occlusion, B detail mask, A smoothness.
        case R::mask_map: return {metal, occ, std::nullopt, smooth};
        // Standard (Specular setup): _SpecGlossMap RGB = specular colour, A = smoothness.
        case R::specular_smoothness: return {std::nullopt, std::nullopt, std::nullopt, smooth};
        case R::mra: return {metal, rough, occ, std::nullopt};
        case R::rma: return {rough, metal, occ, std::nullopt};
        case R::rm: return {rough, metal, std::nullopt, std::nullopt};
        default: break;
    }
    return {};
}

std::vector<std::pair<std::string, std::string>> packing_channels(Role packed) {
    static constexpr const char* kCh[] = {"R", "G", "B", "A"};
    std::vector<std::pair<std::string, std::string>> out;
    const auto layout = packed_layout(packed);
    for (size_t i = 0; i < layout.size(); ++i)
        if (layout[i])
            out.emplace_back(kCh[i], layout[i]->invert ? "smoothness" : std::string(role_name(layout[i]->role)));
    return out;
}

const std::vector<Role>& packed_roles() {
    static const std::vector<Role> kPacked{Role::orm,
                                           Role::metallic_roughness,
                                           Role::ort,
                                           Role::mra,
                                           Role::rma,
                                           Role::rm,
                                           Role::mask_map,
                                           Role::metallic_smoothness,
                                           Role::specular_smoothness};
    return kPacked;
}

}  // namespace mf
