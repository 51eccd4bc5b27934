// Internal to lib/material's sidecar readers (sidecar.cpp: glTF and Megascans JSON;
// materialx.cpp: MaterialX): the paths a sidecar names, and the one way a role is added.
#pragma once
#include <optional>
#include <string>
#include <string_view>

#include "material/discovery.hpp"

namespace mf::sidecar {

// `uri` resolved against the folder of `sidecar` (both relative to the set's root), "." and ".."
// applied, '\' read as '/'. nullopt for data: URIs, absolute paths and URLs, and paths that climb
// out of the set. `decode`: RFC 3986 percent-decoding first (glTF 2.0 §2.8: URIs are encoded).
std::optional<std::string> resolve(std::string_view sidecar, std::string_view uri, bool decode);

// Adds `file` with its role unless the sidecar named the file already (the first role wins).
void add_map(SidecarRoles& out, std::string file, NameMatch m);

// MaterialX (materialx.cpp): fills `out` (kind materialx) or sets out.error.
void read_materialx(std::string_view content, std::string_view source, SidecarRoles& out);

}  // namespace mf::sidecar
