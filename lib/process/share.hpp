// What the presets of one pass share of the set they process in turn (ingest --preset a,b and
// --tiers: process/ingest.hpp run_together), each thing keyed by the values it is made of, never
// by names: the set's decoded maps and validations (plan/plan.hpp PlanShare: by file, and by
// rules config and maps), its input digests (by file), and its encoded outputs (by pack spec,
// colour context and planes: an output's pixels are a function of those, its bytes of its pixels
// and EncodeOptions, since image/image.hpp encodes deterministically; a block-compressed one by
// its preset's text, output, size, colour context and planes). Lives for one set.
// Thread-safe: a set's outputs, of every preset, are packed and encoded on up to two threads.
#pragma once
#include <condition_variable>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "color/color.hpp"
#include "pack/pack.hpp"
#include "plan/plan.hpp"
#include "sets/sets.hpp"
#include "texture/texture.hpp"

namespace mf {

class SetShare {
public:
    explicit SetShare(int plans) : plan(plans) {}
    PlanShare plan;

    // The set's input digests, read and hashed once for every preset of the pass (without a
    // cache, which remembers them by stat: store/cache.hpp).
    std::optional<std::string> digest(const InputFile& in, std::string& error);

    // What an output's pixels are made of: its pack spec, the colour context that converts its
    // colours, and the planes the spec reads.
    struct Source {
        PackSpec spec;
        const ColorContext* color;
        std::shared_ptr<const Planes> planes;
        bool same_as(const Source& o) const;
    };

    // What a block-compressed output (dds, ktx2: texture::encode_output) is made of: the text of
    // its preset but for max_size (the set's size is decided before, plan/plan.cpp; the encoder
    // reads the preset's mips, filters, formats and bounds) with its normal convention, the
    // output's suffix, the size, the colour context and every plane of the set (a roughness mip
    // chain reads the normals' spread: toksvig). The tiers of ingest --tiers at or above a set's
    // size write the same textures.
    struct BlockSource {
        std::string preset;  // Ingestor's encoding_key
        std::string suffix;
        Size size;
        const ColorContext* color;
        std::shared_ptr<const Planes> planes;
        bool same_as(const BlockSource& o) const;
    };

    // An output's place among the set's encodings, taken before any is encoded (ingest posts a
    // set's outputs as tasks, process/ingest.cpp): the first claim of a source leads (encodes
    // it), a later claim of an equal source follows (gets the leader's bytes, its SHA-256 too,
    // waiting while the leader encodes). A follower's task is posted below every leader's, so it
    // is taken after its leader's has started. Equal sources are found by value: the same spec,
    // planes equal pixel for pixel.
    class Claim {
    public:
        bool leads() const { return leader_; }

    private:
        friend class SetShare;
        struct Entry;
        std::shared_ptr<Entry> entry_;
        bool leader_ = false;
        bool settled_ = false;
    };
    std::shared_ptr<Claim> claim(Source source);
    std::shared_ptr<Claim> claim(BlockSource source);

    // `bytes` of a claimed output packed and encoded by `fresh`, and their SHA-256 in `sha`: a
    // follower's bytes are its leader's (neither packed, encoded nor hashed again), or its own
    // from `fresh` where the leader made none (an error, an interrupted run). Its EncodeOptions,
    // the format and bit depth, are in the spec.
    bool encode(Claim& claim, const std::function<bool()>& fresh, std::vector<unsigned char>& bytes, std::string& sha);
    // The same for a block-compressed output: `out` is texture::encode_output's result (bytes,
    // levels, findings).
    bool encode_blocks(Claim& claim, const std::function<bool(texture::EncodedOutput&)>& fresh,
                       texture::EncodedOutput& out);
    // After the claim's output is written, or given up before its encoding (refused, stopped, an
    // exception): a leader that made nothing lets its followers encode their own.
    void settle(Claim& claim);
    // While claims are still to come (a set's presets being planned and their outputs posted,
    // the first preset's already encoding on another thread), every leader's encoding is kept,
    // over the bound too, for a later claim of the same source; end_claims() lets go of those
    // no claim took.
    void begin_claims();
    void end_claims();

private:
    // Counts `planes` and `bytes` against kMaxKeptBytes (planes once); false when over (not kept).
    bool keep_within_bound(const Planes* planes, uint64_t bytes);
    // claim() of a Source or a BlockSource.
    template <class S>
    std::shared_ptr<Claim> claim_of(S source);
    // Drops an entry no claim needs now (done, its followers served, not kept, no claims to
    // come), under mutex_.
    void drop_if_unneeded(const std::shared_ptr<Claim::Entry>& e);
    // A follower's wait for its leader; whether the leader's encoding is there (under `lock`).
    bool wait_for_leader(Claim& claim, std::unique_lock<std::mutex>& lock);

    // Kept up to a bound (planes counted once), for the set's later presets (ingest --preset
    // a,b,c: the third's): an 8K set's planes and outputs are gigabytes, and sharing is a saving,
    // never needed for the result. Over the bound, a leader's encoding is kept only until its
    // followers have it and no claim is to come.
    static constexpr uint64_t kMaxKeptBytes = uint64_t{256} << 20;
    std::mutex mutex_;
    std::condition_variable done_;  // a leader finished
    uint64_t kept_bytes_ = 0;
    bool claiming_ = false;  // between begin_claims() and end_claims()
    std::vector<std::shared_ptr<Claim::Entry>> entries_;
    std::set<const Planes*> counted_;
    std::map<std::string, std::string> digests_;
};

}  // namespace mf
