// What the presets of one pass share of the set they process in turn (ingest --preset a,b and
// --tiers: process/ingest.hpp run_together), each thing keyed by the values it is made of, never
// by names: the set's decoded maps and validations (plan/plan.hpp PlanShare: by file, and by
// rules config and maps), its input digests (by file), and its encoded outputs (by pack spec,
// colour context and planes: an output's pixels are a function of those, its bytes of its pixels
// and EncodeOptions, since image/image.hpp encodes deterministically; a block-compressed one by
// its preset's text, output, size, colour context and planes). Lives for one set.
// Thread-safe: a set's outputs are packed and encoded on up to two threads.
#pragma once
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

    // `bytes` of an output packed and encoded by `fresh`, and their SHA-256 in `sha`: an output
    // of the same source done so before is neither packed, encoded nor hashed again (its
    // EncodeOptions, the format and bit depth, are in the spec). The planes stay with the kept
    // encoding until the set is done.
    bool encode(Source source, const std::function<bool()>& fresh, std::vector<unsigned char>& bytes, std::string& sha);

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

    // `out` encoded by `fresh` (texture::encode_output's result: bytes, levels, findings): an
    // output of the same source done so before is not encoded again. Kept like `encode`'s.
    bool encode_blocks(BlockSource source, const std::function<bool(texture::EncodedOutput&)>& fresh,
                       texture::EncodedOutput& out);

private:
    struct KeptBlocks {
        BlockSource source;
        texture::EncodedOutput encoded;
    };
    // Counts `planes` and `bytes` against kMaxKeptBytes (planes once); false when over (not kept).
    bool keep_within_bound(const Planes* planes, uint64_t bytes);
    struct Kept {
        Source source;
        std::vector<unsigned char> bytes;
        std::string sha;
    };
    // Kept up to a bound (planes counted once): an 8K set's planes and outputs are gigabytes,
    // and sharing is a saving, never needed for the result.
    static constexpr uint64_t kMaxKeptBytes = uint64_t{256} << 20;
    std::mutex mutex_;
    uint64_t kept_bytes_ = 0;
    std::vector<std::shared_ptr<const Kept>> kept_;
    std::vector<std::shared_ptr<const KeptBlocks>> kept_blocks_;
    std::set<const Planes*> counted_;
    std::map<std::string, std::string> digests_;
};

}  // namespace mf
