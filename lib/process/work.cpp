#include "process/work.hpp"

#include <algorithm>
#include <cctype>
#include <numeric>

#include "core/files.hpp"
#include "core/json.hpp"
#include "core/version.hpp"
#include "image/image.hpp"
#include "texture/texture.hpp"

namespace mf {
namespace {

// The key's hash: core's SHA-256 over fields each ended by a newline, so ("ab", "c") never
// hashes as ("a", "bc").
class Hasher {
public:
    void add(std::string_view s) {
        sha_.update(s);
        sha_.update("\n");
    }
    std::string hex() { return sha_.hex(); }

private:
    Sha256 sha_;
};

}  // namespace

std::string context_digest(const Preset& preset, const rules::RuleConfig& rules, const ColorContext& color) {
    Hasher h;
    // The version, not the build: manifests and plans record these keys, and the CLI and the
    // Python extension (two objects, two build-ids) write them alike. The result cache's records
    // name the build besides (store/cache.hpp).
    h.add(kGenerator);
    h.add(image_library_version());                                 // decodes every input, encodes PNG/TIFF/EXR outputs
    h.add(texture::encoder_versions());                             // BCn, ASTC, zstd
    h.add(preset.source_json.dump());                               // sorted keys: the same preset, the same text
    h.add(std::string(convention_name(preset.normal_convention)));  // --normal-convention overrides
    h.add(rules::describe(rules).dump());
    h.add(color.cache_id());
    return h.hex();
}

std::optional<std::string> read_and_hash(const InputFile& in, std::string& error) {
    if (in.bytes) return sha256_hex(*in.bytes);
    if (!in.open_error.empty()) {
        error = in.display + ": " + in.open_error;
        return std::nullopt;
    }
    return sha256_of_file(in.path, error);
}

std::optional<std::string> action_key(const MaterialSource& set, const std::string& context, std::string& error,
                                      const Digest& digest) {
    Hasher h;
    h.add(context);
    // What finding the set brought from how it was found (DUPLICATE_INPUT, NAMES_MERGED: they
    // depend on the inputs given, not on the files) is part of its result, so of its key.
    for (const Finding& f : set.findings) h.add(to_json(f).dump());
    for (const std::string& f : set.files) {  // sorted by find_material_sets
        const InputFile in = set.open(f);
        const std::optional<std::string> sha = digest ? digest(in, error) : read_and_hash(in, error);
        if (!sha) return std::nullopt;
        h.add(f);
        h.add(*sha);
    }
    return h.hex();
}

uint64_t set_bytes(const MaterialSource& set) {
    uint64_t total = 0;
    std::error_code ec;
    if (set.is_zip) {
        const auto b = std::filesystem::file_size(set.root, ec);
        return ec ? 0 : b;
    }
    for (const auto& f : set.files) {
        const auto b = std::filesystem::file_size(set.root / f, ec);
        if (!ec) total += b;
    }
    return total;
}

std::vector<int> assign_shards(const std::vector<MaterialSource>& sets, const std::vector<uint64_t>& bytes, int n) {
    std::vector<size_t> order(sets.size());
    std::iota(order.begin(), order.end(), size_t{0});
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
        return bytes[a] != bytes[b] ? bytes[a] > bytes[b] : sets[a].name < sets[b].name;
    });
    std::vector<uint64_t> load(static_cast<size_t>(std::max(1, n)), 0);
    std::vector<int> shard(sets.size(), 0);
    for (size_t i : order) {
        const auto lightest = std::min_element(load.begin(), load.end()) - load.begin();
        shard[i] = static_cast<int>(lightest);
        load[static_cast<size_t>(lightest)] += std::max<uint64_t>(bytes[i], 1);
    }
    return shard;
}

std::string plan_digest(const std::vector<MaterialSource>& sets, const std::vector<uint64_t>& bytes,
                        const std::vector<int>& shard, int n, const std::string& context) {
    Hasher h;
    h.add(context);
    h.add(std::to_string(n));
    for (size_t i = 0; i < sets.size(); ++i) {
        h.add(sets[i].name);
        h.add(std::to_string(sets[i].files.size()));
        for (const std::string& f : sets[i].files) h.add(f);
        h.add(std::to_string(bytes[i]));
        h.add(std::to_string(shard[i]));
    }
    return h.hex();
}

std::optional<std::pair<int, int>> parse_shard(const std::string& spec) {
    const auto slash = spec.find('/');
    if (slash == std::string::npos || slash == 0 || slash + 1 == spec.size()) return std::nullopt;
    const std::string a = spec.substr(0, slash), b = spec.substr(slash + 1);
    auto digits = [](const std::string& s) { return s.size() <= 6 && std::all_of(s.begin(), s.end(), ::isdigit); };
    if (!digits(a) || !digits(b)) return std::nullopt;
    const int i = std::stoi(a), n = std::stoi(b);
    if (n < 1 || i >= n) return std::nullopt;
    return std::pair{i, n};
}

}  // namespace mf
