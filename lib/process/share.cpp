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
    uint64_t size = bytes.size();
    if (!counted_.count(source.planes.get()))
        for (const auto& [r, p] : *source.planes) size += p.codes.pixels.size() + p.image.pixels.size() * sizeof(float);
    if (kept_bytes_ + size > kMaxKeptBytes) return true;
    kept_bytes_ += size;
    counted_.insert(source.planes.get());
    kept_.push_back(std::make_shared<const Kept>(Kept{std::move(source), bytes, sha}));
    return true;
}

}  // namespace mf
