#include "process/share.hpp"

#include <algorithm>
#include <type_traits>

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

// One source's encoding: its leader's result, for its followers.
struct SetShare::Claim::Entry {
    std::optional<Source> pixels;  // what it is made of: one of the two
    std::optional<BlockSource> blocks;
    bool done = false;                 // the leader is finished, with or without a result
    bool has_result = false;           // the leader encoded it
    bool kept = false;                 // within the bound: kept for claims to come
    int followers = 0;                 // claims that have not had it yet
    std::vector<unsigned char> bytes;  // a pixel output's, and its SHA-256
    std::string sha;
    std::optional<texture::EncodedOutput> encoded;  // a block-compressed output's
    const std::optional<Source>& source(const Source*) const { return pixels; }
    const std::optional<BlockSource>& source(const BlockSource*) const { return blocks; }
    const Planes* planes() const { return pixels ? pixels->planes.get() : blocks->planes.get(); }
};

template <class S>
std::shared_ptr<SetShare::Claim> SetShare::claim_of(S source) {
    auto c = std::make_shared<Claim>();
    std::lock_guard lock(mutex_);
    for (const auto& e : entries_) {
        const std::optional<S>& s = e->source(static_cast<const S*>(nullptr));
        // (A leader that made nothing has nothing to give: the claim leads anew.)
        if (s && !(e->done && !e->has_result) && s->same_as(source)) {
            ++e->followers;
            c->entry_ = e;
            return c;
        }
    }
    c->entry_ = std::make_shared<Claim::Entry>();
    if constexpr (std::is_same_v<S, Source>) c->entry_->pixels = std::move(source);
    else c->entry_->blocks = std::move(source);
    c->leader_ = true;
    entries_.push_back(c->entry_);
    return c;
}

std::shared_ptr<SetShare::Claim> SetShare::claim(Source source) { return claim_of(std::move(source)); }
std::shared_ptr<SetShare::Claim> SetShare::claim(BlockSource source) { return claim_of(std::move(source)); }

bool SetShare::keep_within_bound(const Planes* planes, uint64_t bytes) {
    uint64_t size = bytes;
    if (!counted_.count(planes))
        for (const auto& [r, p] : *planes) size += p.codes.pixels.size() + p.image.pixels.size() * sizeof(float);
    if (kept_bytes_ + size > kMaxKeptBytes) return false;
    kept_bytes_ += size;
    counted_.insert(planes);
    return true;
}

void SetShare::drop_if_unneeded(const std::shared_ptr<Claim::Entry>& e) {
    if (!e->done || e->followers > 0 || e->kept || (claiming_ && e->has_result)) return;
    e->bytes = {};
    e->encoded.reset();
    std::erase(entries_, e);
}

bool SetShare::wait_for_leader(Claim& claim, std::unique_lock<std::mutex>& lock) {
    Claim::Entry& e = *claim.entry_;
    done_.wait(lock, [&] { return e.done; });
    --e.followers;
    claim.settled_ = true;
    const bool had = e.has_result;
    return had;
}

bool SetShare::encode(Claim& claim, const std::function<bool()>& fresh, std::vector<unsigned char>& bytes,
                      std::string& sha) {
    const std::shared_ptr<Claim::Entry> e = claim.entry_;
    if (!claim.leader_) {
        std::unique_lock lock(mutex_);
        const bool had = wait_for_leader(claim, lock);
        if (had) {
            bytes = e->bytes;
            sha = e->sha;
        }
        drop_if_unneeded(e);
        if (had) return true;
    }
    if (!fresh()) return false;  // settle() tells the followers
    sha = sha256_hex(bytes);
    if (!claim.leader_) return true;
    std::lock_guard lock(mutex_);
    e->kept = keep_within_bound(e->planes(), bytes.size());
    if (e->kept || e->followers > 0 || claiming_) {
        e->bytes = bytes;
        e->sha = sha;
    }
    e->has_result = e->done = claim.settled_ = true;
    done_.notify_all();
    drop_if_unneeded(e);
    return true;
}

bool SetShare::encode_blocks(Claim& claim, const std::function<bool(texture::EncodedOutput&)>& fresh,
                             texture::EncodedOutput& out) {
    const std::shared_ptr<Claim::Entry> e = claim.entry_;
    if (!claim.leader_) {
        std::unique_lock lock(mutex_);
        const bool had = wait_for_leader(claim, lock);
        if (had) out = *e->encoded;
        drop_if_unneeded(e);
        if (had) return true;
    }
    if (!fresh(out)) return false;
    if (!claim.leader_) return true;
    std::lock_guard lock(mutex_);
    e->kept = keep_within_bound(e->planes(), out.bytes.size());
    if (e->kept || e->followers > 0 || claiming_) e->encoded = out;
    e->has_result = e->done = claim.settled_ = true;
    done_.notify_all();
    drop_if_unneeded(e);
    return true;
}

void SetShare::begin_claims() {
    std::lock_guard lock(mutex_);
    claiming_ = true;
}

void SetShare::end_claims() {
    std::lock_guard lock(mutex_);
    claiming_ = false;
    for (const auto& e : std::vector(entries_)) drop_if_unneeded(e);
}

void SetShare::settle(Claim& claim) {
    std::lock_guard lock(mutex_);
    if (claim.settled_) return;
    claim.settled_ = true;
    if (claim.leader_) {
        claim.entry_->done = true;
        done_.notify_all();
    } else {
        --claim.entry_->followers;
    }
    drop_if_unneeded(claim.entry_);
}

}  // namespace mf
