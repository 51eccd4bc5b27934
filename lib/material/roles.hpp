// The one role-traits table: what each map means and how it is encoded.
#pragma once
#include <array>
#include <optional>
#include <string_view>

namespace mf {

// Output roles first; input-only roles after `opacity` (docs/interface.md "Words").
enum class Role {
    albedo,
    normal,
    roughness,
    metalness,
    occlusion,
    height,
    emissive,
    opacity,
    // input-only
    gloss,               // inverted into roughness
    specular,            // kept in the manifest, reported, not packed
    orm,                 // packed: R occlusion, G roughness, B metalness (also "ARM")
    metallic_roughness,  // glTF packed: G roughness, B metalness
    ort,                 // Megascans packed: R occlusion, G roughness, B translucency
    cavity,              // Megascans cavity: reported, not packed
    translucency,        // Megascans / Poliigon SSS: reported, not packed
};
inline constexpr int kRoleCount = 15;
inline constexpr int kOutputRoleCount = 8;

enum class NormalConvention { unknown, gl, dx };  // gl: +Y (green up), dx: -Y

struct RoleTraits {
    Role role;
    std::string_view name;
    bool output;   // can appear in an output texture
    bool color;    // albedo and emissive: color, sRGB-encoded in 8/16-bit files; all else is data
    int channels;  // 3 for color/normal/packed, 1 for scalars
    bool packed;   // an input that is split into several roles
};

const RoleTraits& traits(Role r);
std::string_view role_name(Role r);
std::optional<Role> role_from_name(std::string_view name);
std::string_view convention_name(NormalConvention c);  // "unknown" | "gl" | "dx"
std::optional<NormalConvention> convention_from_name(std::string_view name);
inline bool is_output_role(Role r) { return traits(r).output; }
inline bool is_color_role(Role r) { return traits(r).color; }

// Channels of a packed input: which output role each of R, G, B holds (nullopt = not unpacked).
std::array<std::optional<Role>, 3> packed_layout(Role packed);

}  // namespace mf
