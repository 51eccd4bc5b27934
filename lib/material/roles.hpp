// The one role-traits table: what each map means and how it is encoded.
#pragma once
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

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
    // Packed inputs of engine exports (docs/ingest.md "Packed maps"); smoothness is inverted.
    metallic_smoothness,  // Unity Standard/URP: R metalness, A smoothness (G, B unused)
    mask_map,             // Unity HDRP: R metalness, G occlusion, B detail mask (unused), A smoothness
    specular_smoothness,  // Unity specular workflow: RGB specular (kept), A smoothness
    mra,                  // "_MRA", "_MRAO": R metalness, G roughness, B occlusion
    rma,                  // "_RMA", "_RMAO": R roughness, G metalness, B occlusion
    rm,                   // "_RoughnessMetallic": R roughness, G metalness
    // The vendor's own picture of the material (ambientCG "<id>.png", Poliigon "_Preview1",
    // Megascans "_Preview", 3dtextures.me "Material_NNNN"): recorded and shown, never read as a
    // map, validated or packed (discovery.hpp SetDiscovery::preview).
    preview,
};
inline constexpr int kRoleCount = 22;
inline constexpr int kOutputRoleCount = 8;

enum class NormalConvention { unknown, gl, dx };                      // gl: +Y (green up), dx: -Y
enum class NormalSpace : unsigned char { unknown, tangent, object };  // what a normal map's name says of its space

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

// One channel of a packed input: the role it holds, stored inverted (smoothness = 1 - roughness).
struct PackedChannel {
    Role role = Role::albedo;
    bool invert = false;
};
// Channels of a packed input: what each of R, G, B, A holds (nullopt = not unpacked: unused,
// a detail mask, the specular colour). The one owner of every packing matforge reads.
using PackedLayout = std::array<std::optional<PackedChannel>, 4>;
PackedLayout packed_layout(Role packed);
// The packing as words, channel by channel: {"R", "metalness"}, {"A", "smoothness"} (an
// inverted channel is named smoothness). Empty for a role that is not packed.
std::vector<std::pair<std::string, std::string>> packing_channels(Role packed);
// Every packed input role, in routing preference order (the first holding a role feeds it).
const std::vector<Role>& packed_roles();

}  // namespace mf
