#include "process/share.hpp"

#include <algorithm>

#include "core/files.hpp"
#include "process/work.hpp"

namespace mf {

std::optional<std::string> SetShare::digest(const InputFile& in, std::string& error) {
    const std::string key = in.display + '\n' + in.path.string();
    {
        std::lock_guard lock(mutex_);
        if (const auto it = digests_.find(key); it != digests_.end()) return it->second;
    }
    std::optional<std::string> sha = read_and_hash(in, error);
    if (sha) {
        std::lock_guard lock(mutex_);
        digests_.emplace(key, *sha);
    }
    return sha;
}

bool SetShare::Source::same_as(const Source& o) const {
    return spec == o.spec && color == o.color &&
           (planes == o.planes || std::all_of(spec.roles.begin(), spec.roles.end(),
                                              [&](Role r) { return same_plane(planes->at(r), o.planes->at(r)); }));
}

bool SetShare::keep_within_bound(const Planes* planes, uint64_t bytes) {
    uint64_t size = bytes;
    if (!counted_.count(planes))
        for (const auto& [r, p] : *planes) size += p.codes.pixels.size() + p.image.pixels.size() * sizeof(float);
    if (kept_bytes_ + size > kMaxKeptBytes) return false;
    kept_bytes_ += size;
    counted_.insert(planes);
    return true;
}

bool SetShare::encode(Source source, const std::function<bool()>& fresh, std::vector<unsigned char>& bytes,
                      std::string& sha) {
    std::vector<std::shared_ptr<const Kept>> kept_now;
    {
        std::lock_guard lock(mutex_);
        kept_now = kept_;
    }
    // Compared outside the lock (another output of the set may be packing meanwhile).
    for (const auto& k : kept_now)
        if (k->source.same_as(source)) {
            bytes = k->bytes;
            sha = k->sha;
            return true;
        }
    if (!fresh()) return false;
    sha = sha256_hex(bytes);
    std::lock_guard lock(mutex_);
    if (!keep_within_bound(source.planes.get(), bytes.size())) return true;
    kept_.push_back(std::make_shared<const Kept>(Kept{std::move(source), bytes, sha}));
    return true;
}

bool SetShare::BlockSource::same_as(const BlockSource& o) const {
    if (preset != o.preset || suffix != o.suffix || !(size == o.size) || color != o.color) return false;
    if (planes == o.planes) return true;
    if (planes->size() != o.planes->size()) return false;
    for (const auto& [role, plane] : *planes) {
        const auto other = o.planes->find(role);
        if (other == o.planes->end() || !same_plane(plane, other->second)) return false;
    }
    return true;
}

bool SetShare::encode_blocks(BlockSource source, const std::function<bool(texture::EncodedOutput&)>& fresh,
                             texture::EncodedOutput& out) {
    std::vector<std::shared_ptr<const KeptBlocks>> kept_now;
    {
        std::lock_guard lock(mutex_);
        kept_now = kept_blocks_;
    }
    for (const auto& k : kept_now)
        if (k->source.same_as(source)) {
            out = k->encoded;
            return true;
        }
    if (!fresh(out)) return false;
    std::lock_guard lock(mutex_);
    if (!keep_within_bound(source.planes.get(), out.bytes.size())) return true;
    kept_blocks_.push_back(std::make_shared<const KeptBlocks>(KeptBlocks{std::move(source), out}));
    return true;
}

}  // namespace mf
