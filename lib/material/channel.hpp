// What one channel (or the RGB triple) of a texture holds: a preset says it of the outputs it
// wants (preset/preset.hpp ChannelSpec), a manifest of the outputs written (manifest.hpp).
#pragma once
#include <string>

#include "material/roles.hpp"

namespace mf {

struct Channel {
    enum class Kind { role, smoothness, constant, unused };
    std::string key;  // "RGB", "R", "G", "B", "A"
    Kind kind = Kind::unused;
    Role role = Role::albedo;  // kind == role (and smoothness: roughness, stored as 1 - roughness)
    float value = 0.f;         // kind == constant
    bool operator==(const Channel&) const = default;
};

}  // namespace mf
