#include <algorithm>
#include <vector>

#include "material/sidecar_util.hpp"

namespace mf::sidecar {
namespace {

int hex_value(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

// RFC 3986 percent-decoding (glTF 2.0 §2.8: URIs are encoded); a malformed escape stays as is.
std::string percent_decode(std::string_view s) {
    std::string out;
    for (size_t i = 0; i < s.size(); ++i) {
        if (s[i] == '%' && i + 2 < s.size()) {
            const int hi = hex_value(s[i + 1]), lo = hex_value(s[i + 2]);
            if (hi >= 0 && lo >= 0) {
                out += static_cast<char>(hi * 16 + lo);
                i += 2;
                continue;
            }
        }
        out += s[i];
    }
    return out;
}

}  // namespace

std::optional<std::string> resolve(std::string_view sidecar, std::string_view uri, bool decode) {
    if (uri.empty() || uri.starts_with("data:") || uri.find("://") != std::string_view::npos) return std::nullopt;
    std::string path = decode ? percent_decode(uri) : std::string(uri);
    std::replace(path.begin(), path.end(), '\\', '/');
    if (path.starts_with('/') || (path.size() > 1 && path[1] == ':')) return std::nullopt;  // "/x", "C:/x"
    std::string dir(sidecar);
    std::replace(dir.begin(), dir.end(), '\\', '/');
    const auto slash = dir.rfind('/');
    dir = slash == std::string::npos ? std::string() : dir.substr(0, slash + 1);
    std::vector<std::string> parts;
    const std::string full = dir + path;
    size_t start = 0;
    for (size_t p = 0; p <= full.size(); ++p) {
        if (p < full.size() && full[p] != '/') continue;
        const std::string part = full.substr(start, p - start);
        start = p + 1;
        if (part.empty() || part == ".") continue;
        if (part == "..") {
            if (parts.empty()) return std::nullopt;
            parts.pop_back();
            continue;
        }
        parts.push_back(part);
    }
    if (parts.empty()) return std::nullopt;
    std::string out;
    for (const auto& part : parts) out += (out.empty() ? "" : "/") + part;
    return out;
}

void add_map(SidecarRoles& out, std::string file, NameMatch m) {
    for (const auto& existing : out.maps)
        if (existing.file == file) return;  // first role wins
    std::sort(m.unused.begin(), m.unused.end());
    out.maps.push_back({std::move(file), std::move(m)});
}

}  // namespace mf::sidecar
