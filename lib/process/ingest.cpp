#include "process/ingest.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <set>
#include <thread>
#include <tuple>

#include "base/interrupt.hpp"
#include "base/limits.hpp"
#include "base/parallel.hpp"
#include "core/files.hpp"
#include "core/json.hpp"
#include "core/version.hpp"
#include "findings/catalog.hpp"
#include "manifest/spool.hpp"
#include "pack/pack.hpp"
#include "plan/plan.hpp"
#include "preset/texture_fields.hpp"
#include "process/material_file.hpp"
#include "process/share.hpp"
#include "process/work.hpp"
#include "store/cache.hpp"
#include "store/output_dir.hpp"
#include "texture/texture.hpp"

namespace mf {
namespace fs = std::filesystem;
namespace {

std::string relative_to(const fs::path& p, const fs::path& base) {
    std::error_code ec;
    const fs::path a = fs::absolute(p, ec).lexically_normal();
    const fs::path b = fs::absolute(base, ec).lexically_normal();
    fs::path r = a.lexically_relative(b);
    if (r.empty()) r = a;
    return r.generic_string();
}

std::string source_of(const MaterialSource& s, const fs::path& out_dir) {
    return relative_to(s.root, out_dir) + (s.is_zip && !s.zip_folder.empty() ? "/" + s.zip_folder : "");
}

// The channels as written: what the preset asked for, without its "optional" flag.
std::vector<manifest::Channel> manifest_channels(const std::vector<ChannelSpec>& channels) {
    return {channels.begin(), channels.end()};
}

template <class T>
BasicImage<T> first_two_channels(const BasicImage<T>& src) {
    BasicImage<T> out(src.width, src.height, 2);
    const size_t n = static_cast<size_t>(src.width) * src.height;
    for (size_t p = 0; p < n; ++p) {
        out.pixels[2 * p] = src.pixels[p * static_cast<size_t>(src.channels)];
        out.pixels[2 * p + 1] = src.pixels[p * static_cast<size_t>(src.channels) + 1];
    }
    return out;
}

// An emissive map with radiance above 1 (an EXR, an HDR) written to an integer file would clip
// to white and lose its hue: it is stored as emissive / S, S its brightest channel, and S is
// returned for the manifest (`emissive_strength`) and the glTF (KHR_materials_emissive_strength).
// 1 when nothing is scaled: no emissive map, one at most 1, or float outputs (EXR, 32-bit).
float normalize_hdr_emissive(Planes& planes, const Preset& preset) {
    const auto it = planes.find(Role::emissive);
    if (it == planes.end() || it->second.is_codes() || it->second.encoding != ColorEncoding::linear) return 1.f;
    bool integer_output = false;
    for (const auto& o : preset.outputs) {
        const auto roles = o.roles();
        if (std::find(roles.begin(), roles.end(), Role::emissive) != roles.end())
            integer_output = integer_output || (preset.format != FileFormat::exr && o.bit_depth != 32);
    }
    Image& img = it->second.image;
    float brightest = 0.f;
    const auto c = static_cast<size_t>(img.channels);
    for (size_t i = 0; i < img.pixels.size(); ++i)
        if (i % c < 3 && std::isfinite(img.pixels[i])) brightest = std::max(brightest, img.pixels[i]);
    if (!integer_output || brightest <= 1.f) return 1.f;
    for (size_t i = 0; i < img.pixels.size(); ++i)
        if (i % c < 3) img.pixels[i] /= brightest;
    return brightest;
}

// Canonical planes per output role from the plan's routes (pack/pack.hpp's conventions), made
// from the decoded maps, which other plans of the set may be reading (plan/plan.hpp SharedMap).
// A map is let go after its last plane is made: peak memory is one set's maps and planes.
Planes make_planes(SetPlan& plan) {
    std::map<std::string, int> uses;
    for (const auto& [out, r] : plan.routes) ++uses[plan.inputs.at(r.from).file];
    Planes planes;
    for (const auto& [out, route] : plan.routes) {
        const std::string& file = plan.inputs.at(route.from).file;
        const SharedMap& held = plan.decoded.at(file);
        const bool last_use = --uses[file] == 0;
        const DecodedMap& l = *held;
        const Decoded& img = l.img;
        // At its last use by the only plan still holding it (the share has let go: no other plan
        // can reach it), a map's image that is the plane as it is moves into the plane instead of
        // being copied (the map was made mutable by read_map; SharedMap's const is for readers).
        Decoded* own = last_use && held.use_count() == 1 ? &const_cast<DecodedMap&>(l).img : nullptr;
        RolePlane plane;
        if (out == Role::albedo || out == Role::emissive) {
            if (img.is_codes())
                plane.codes = own && img.codes.channels == 3 ? std::move(own->codes) : to_rgb(img.codes);
            else plane.image = own && img.floats.channels == 3 ? std::move(own->floats) : to_rgb(img.floats);
            plane.encoding = l.info.is_float ? ColorEncoding::linear : ColorEncoding::srgb;
        } else if (out == Role::normal) {
            // An empty blue is dropped: the two-channel path rebuilds Z from X and Y.
            const bool xy = plan.normal_z_rebuilt && img.channels() >= 3;
            if (img.is_codes()) {  // decoded when packed (pack_output8) or resampled (fit_plane)
                if (xy) plane.codes = first_two_channels(img.codes);
                else if (own) plane.codes = std::move(own->codes);
                else plane.codes = img.codes;
                plane.codes_convention = plan.normal_from();
            } else if (xy) {
                decode_normal(first_two_channels(img.floats), plan.normal_from(), plane.image);
            } else {
                decode_normal(img.floats, plan.normal_from(), plane.image);
            }
        } else {
            const int ch = route.channel < 0 ? 0 : route.channel;
            if (img.is_codes()) {
                plane.codes = own && img.codes.channels == 1 ? std::move(own->codes) : extract_channel(img.codes, ch);
                if (route.invert) invert(plane.codes);
            } else {
                plane.image = own && img.floats.channels == 1 ? std::move(own->floats)
                                                              : extract_channel(img.floats, ch);
                if (route.invert) invert(plane.image);
            }
        }
        if (last_use) plan.decoded.erase(file);
        planes.emplace(out, std::move(plane));
    }
    plan.decoded.clear();  // planes hold what is needed from here on
    return planes;
}

// A set's presets planned before their outputs are written, together (run_together): two, so
// a set holds at most two presets' planes, what its plan's lease counts (plan/plan.cpp: its maps
// and the planes made of them).
constexpr size_t kPresetsAtOnce = 2;

// Counts a set as running until it is done or throws.
struct InFlight {
    std::atomic<int>& n;
    explicit InFlight(std::atomic<int>& c) : n(c) { ++n; }
    ~InFlight() { --n; }
    InFlight(const InFlight&) = delete;
    InFlight& operator=(const InFlight&) = delete;
};

}  // namespace

Ingestor::Ingestor(Preset preset, std::shared_ptr<const ColorContext> color, IngestOptions opt)
    : preset_(std::move(preset)), color_(std::move(color)), opt_(std::move(opt)) {
    // --normal-convention overrides the preset everywhere: choice, conversion, encoding, manifest.
    if (opt_.normal_override) preset_.normal_convention = *opt_.normal_override;
    nlohmann::json text = preset_.source_json;
    if (text.is_object()) text.erase("max_size");
    encoding_key_ = text.dump() + '\n' + std::string(convention_name(preset_.normal_convention));
}

// One preset's part of a pass: everything run() alone holds for its run. open() before the
// sets, record() after each (serialized), finish() at the end; process() and compute() read the
// run's folder, claims, context, cache and the pass's in-flight count through it.
struct Ingestor::PresetRun {
    explicit PresetRun(const Ingestor& i) : ing(i) {}

    const Ingestor& ing;
    IngestResult result;
    bool ready = false;  // open() went well: the sets run
    // The output folder, ours for the run (lock, journal, files that are not ours refused:
    // store/output_dir.hpp): every file of the run is written through it.
    std::unique_ptr<OutputFolder> folder;
    // The outputs whose paths another output claimed first: material -> suffix -> why.
    std::map<std::string, std::map<std::string, std::string>> refused;
    // The digest of everything but a set's files (process/work.hpp context_digest): the cache's
    // keys and a shard's run.
    std::string context;
    std::string split;  // a shard's: the digest of the library's split (merge checks the parts)
    std::optional<Cache> cache_store;
    Cache* cache = nullptr;  // null: no cache (--no-cache, or it could not be opened)
    std::mutex mutex;
    std::atomic<size_t> hits{0}, misses{0};
    std::atomic<bool> cache_off{false};  // after a store failed: the cache is off for the rest of the run
    std::vector<std::string> cache_problems;
    // Each set's entry goes to the spool (a temporary file) when the set is done: the run holds
    // a tally and the file names of each set, not its entry (manifest/spool.hpp).
    std::unique_ptr<manifest::MaterialSpool> spool;
    std::string spool_error;
    std::set<std::string> produced;  // every file the run wrote, for the folder's stale removal
    size_t done = 0;

    // Through the folder (a unique_ptr: its constness is not the run's).
    bool write(const std::string& rel, std::span<const unsigned char> bytes, std::string& error) const {
        return folder->write(rel, bytes, error);
    }
    void cache_problem(std::string p) {
        std::lock_guard<std::mutex> lock(mutex);
        cache_problems.push_back(std::move(p));
    }
    // Everything before the sets, on `batch` (already cut to the run's shard): the folder made
    // and opened, every output path claimed, the cache, the spool. `ready` says it went well,
    // else result.error (and usage_error) says why.
    void open(const Batch& batch, std::string split_digest);
    // Set `set`'s result into the spool and the tallies; `total`: the batch's sets (progress).
    void record(const MaterialSource& set, MaterialResult&& r, size_t total);
    // After every set: the manifest's head, the folder's and library files, the manifest written
    // and the folder finished (store/output_dir.hpp), or result.error.
    void finish(const Batch& batch);
};

namespace {

// One output of a set: what writing it needs of its set and its run.
struct OutputJob {
    const Preset& preset;
    const ColorContext& color;
    const SetPlan& plan;
    const Planes& planes;
    const std::string& set_name;
    Size size;                                          // the set's size (the planes')
    const std::map<std::string, std::string>* refused;  // output suffix -> why it may not be written
    std::function<bool(const std::string& rel, std::span<const unsigned char>, std::string& error)>
        write;  // the run's folder
    // Packs and encodes an output of `size` in the preset's image format: through the set's share
    // in run_together, which also gives the bytes' SHA-256 (else left empty).
    std::function<bool(const OutputSpec&, Size, std::vector<unsigned char>&, std::string& sha, std::string&)>
        pack_encode;
    // The same for a block-compressed container (dds, ktx2): texture::encode_output, through the
    // set's share in run_together.
    std::function<bool(const OutputSpec&, Size, texture::EncodedOutput&, std::string&)> encode_blocks;
};

struct Written {
    std::optional<manifest::Output> entry;  // set when written
    std::optional<Finding> failure;
    std::vector<Finding> notes;  // block-compressed outputs: resized top level, error over the bound
};

// An output's size: the set's, or the preset's constant size for one made of constants only.
Size output_size(const OutputSpec& o, const Planes& planes, const Preset& preset, Size set_size) {
    const auto roles = o.roles();
    const bool any_map = std::any_of(roles.begin(), roles.end(), [&](Role r) { return planes.count(r) > 0; });
    return any_map ? set_size : Size{preset.constant_size, preset.constant_size};
}

// What packing and encoding an output costs, roughly: enough to start a set's largest outputs
// first (run_together). Its samples, block compression weighing more than deflate (measured on
// the corpus: a BC7 or ASTC level with its mips takes several times a PNG's time).
uint64_t output_cost(const OutputSpec& o, Size size, const Preset& preset) {
    constexpr uint64_t kBlockWeight = 8;
    const uint64_t samples = static_cast<uint64_t>(std::max(size.width, 1)) *
                             static_cast<uint64_t>(std::max(size.height, 1)) *
                             static_cast<uint64_t>(std::max(o.channel_count(), 1)) *
                             static_cast<uint64_t>(o.bit_depth > 8 ? 2 : 1);
    return samples * (is_block_container(preset.format) ? kBlockWeight : 1);
}

// Packs, encodes and writes one output through the run's folder; its manifest entry, or why not.
Written write_output(const OutputSpec& o, const OutputJob& job) {
    auto failed = [](std::string msg) {
        return Written{std::nullopt, finding(code::output_write_failed, "", "", std::move(msg)), {}};
    };
    const std::string rel = job.preset.output_path(job.set_name, o);
    const fs::path rel_path = fs::path(rel).lexically_normal();
    if (rel_path.is_absolute() || rel_path.empty() || *rel_path.begin() == "..")
        return failed("output path '" + rel + "' leaves the output folder; skipped");
    if (job.refused)
        if (const auto why = job.refused->find(o.suffix); why != job.refused->end())
            return failed(why->second + "; not written");
    if (stop_requested()) return failed(rel + ": not written (interrupted)");
    const auto roles = o.roles();
    const Size size = output_size(o, job.planes, job.preset, job.size);
    std::vector<unsigned char> bytes;
    std::string sha;  // of `bytes`, when the encoder had it
    std::string err;
    bool encoded = false;
    std::optional<texture::EncodedOutput> gpu;  // dds, ktx2: the mip levels in GPU blocks (lib/texture)
    if (is_block_container(job.preset.format)) {
        gpu.emplace();
        encoded = job.encode_blocks(o, size, *gpu, err);
        bytes = std::move(gpu->bytes);
    } else {
        encoded = job.pack_encode(o, size, bytes, sha, err);
    }
    // Written through the run's folder: under it, never through a link, journalled.
    const std::string file = rel_path.generic_string();
    if (!encoded) return failed(rel + ": " + err);
    if (!job.write(file, bytes, err)) return failed(err.rfind(file, 0) == 0 ? err : rel + ": " + err);
    manifest::Output e;
    e.file = rel_path.generic_string();
    e.srgb = o.srgb;
    e.channels = manifest_channels(effective_channels(o, job.planes));
    if (std::find(roles.begin(), roles.end(), Role::normal) != roles.end()) {
        e.normal_convention = job.preset.normal_convention;
        // The one owner of "the green channel was flipped" (the report reads it here).
        if (job.plan.routes.count(Role::normal) && job.plan.normal_from() != job.preset.normal_convention)
            e.normal_converted_from = job.plan.normal_from();
    }
    e.width = size.width;
    e.height = size.height;
    e.bit_depth = o.bit_depth;
    e.format = std::string(word(job.preset.format));
    e.sha256 = sha.empty() ? sha256_hex(bytes) : std::move(sha);
    if (!gpu) return Written{std::move(e), std::nullopt, {}};
    e.width = gpu->width;
    e.height = gpu->height;
    e.block_format = gpu->block_format;
    e.gpu_format = gpu->gpu_format;
    e.supercompression = gpu->supercompression;
    e.normal_z_reconstructed = gpu->normal_xy;
    e.levels = std::move(gpu->levels);
    e.dilated_texels = gpu->dilated_texels;
    return Written{std::move(e), std::nullopt, std::move(gpu->findings)};
}

// GPUs and engines import at most kMaxImageSide pixels a side (base/limits.hpp): a larger
// output is written, and said so (once a set: the first such output).
std::optional<Finding> too_large(const std::vector<Written>& written) {
    for (const auto& r : written)
        if (r.entry && std::max(r.entry->width, r.entry->height) > kMaxImageSide)
            return finding(code::output_too_large, "", "",
                           r.entry->file + " is " + std::to_string(r.entry->width) + "x" +
                               std::to_string(r.entry->height) + ": wider or taller than " +
                               std::to_string(kMaxImageSide) +
                               " pixels, which engines and GPUs do not import; downsample the source or set "
                               "the preset's max_size",
                           {{"size", {r.entry->width, r.entry->height}}, {"limit", kMaxImageSide}});
    return std::nullopt;
}

}  // namespace

// One preset's part of a set in a pass, from begin() to end(): the set restored from the cache
// (`result`), or its plan, its planes and the outputs its tasks write.
struct Ingestor::SetWork {
    SetWork(const MaterialSource& s, PresetRun& r, SetShare* sh) : src(s), run(r), share(sh) {}
    const MaterialSource& src;
    PresetRun& run;
    SetShare* share;
    // The set's action key (its entry's, when complete), and the cache's key when it may be
    // restored from or stored into the cache.
    std::optional<std::string> action, key;
    std::optional<MaterialResult> result;  // restored, or failed before any output
    bool restored = false;
    SetPlan plan;
    std::shared_ptr<const Planes> planes;  // shared with the set's share
    float emissive_strength = 1.f;
    std::vector<const OutputSpec*> wanted;  // preset order
    std::vector<Written> written;           // wanted[i]'s, by its task
    // wanted[i]'s place among the set's encodings (a pass of several presets; else null).
    std::vector<std::shared_ptr<SetShare::Claim>> claims;
    // The set's files are finished (fsync, journal, rename) by the folder's committer while the
    // next output is packed and encoded; the outputs are in place before the material files
    // that name them are written, and those before the set's entry is returned.
    std::unique_ptr<OutputFolder::Batch> batch;
};

std::unique_ptr<Ingestor::SetWork> Ingestor::begin(const MaterialSource& src, const SetStage& stage, PresetRun& run,
                                                   SetShare* share) const {
    auto work = std::make_unique<SetWork>(src, run, share);
    // Sets whose outputs another set claimed first are computed (the refusals are this run's).
    const bool cacheable = run.cache && !run.cache_off && !run.refused.count(src.name);
    // Every set's action key goes into its entry (plan --changed-since); the cache remembers its
    // files' digests by stat, without it they are read and hashed.
    std::string key_error;
    Digest digest;
    if (run.cache) digest = [&](const InputFile& in, std::string& e) { return run.cache->digest(in, e); };
    else if (share) digest = [share](const InputFile& in, std::string& e) { return share->digest(in, e); };
    work->action = action_key(src, run.context, key_error, digest);
    if (cacheable) work->key = work->action;
    if (work->key) {
        auto write = [&run](const std::string& rel, std::span<const unsigned char> b, std::string& e) {
            return run.write(rel, b, e);
        };
        std::vector<std::string> corrupt;
        auto hit = run.cache->restore(*work->key, src.name, opt_.out_dir, write, corrupt);
        for (auto& c : corrupt) run.cache_problem(src.display + ": " + c + "; the set was computed again");
        if (hit) {
            ++run.hits;
            MaterialResult& res = work->result.emplace();
            res.entry = std::move(hit->entry);
            res.entry.key = *work->key;
            res.entry.source = source_of(src, opt_.out_dir);
            if (src.is_zip) res.entry.archive = relative_to(src.root, opt_.out_dir);
            work->restored = true;
            return work;
        }
    }

    work->plan = plan_set(src, PlanOptions{&preset_, &opt_.rules, PlanMode::decode, stage.budget, stage.spare_core,
                                           share ? &share->plan : nullptr});
    SetPlan& plan = work->plan;
    if (plan.failure) {
        work->result.emplace().failure = std::move(plan.failure);
        return work;
    }
    // Shared with the set's share, which keeps them with the encodings made from them.
    const auto made = std::make_shared<Planes>(make_planes(plan));
    for (auto& [r, p] : *made) fit_plane(r, p, plan.width, plan.height, *color_);
    work->emissive_strength = normalize_hdr_emissive(*made, preset_);
    work->planes = made;

    remove_stale_temps(opt_.out_dir / src.name, /*other_hosts=*/true);  // only this set writes here
    for (const auto& o : preset_.outputs)
        if (output_needed(o, *work->planes)) work->wanted.push_back(&o);
    work->written.resize(work->wanted.size());
    work->claims.resize(work->wanted.size());
    work->batch = std::make_unique<OutputFolder::Batch>(*run.folder);
    return work;
}

void Ingestor::post_outputs(SetWork& work, SpareTasks& tasks) const {
    if (work.result) return;
    const Size set_size{work.plan.width, work.plan.height};
    for (size_t i = 0; i < work.wanted.size(); ++i) {
        const OutputSpec& o = *work.wanted[i];
        const Size size = output_size(o, *work.planes, preset_, set_size);
        // An output equal to one another preset of the pass writes for the set is encoded once:
        // the first claim encodes, the others wait for its bytes, so they go last.
        std::shared_ptr<SetShare::Claim>& claim = work.claims[i];
        if (work.share && is_block_container(preset_.format))
            claim = work.share->claim(SetShare::BlockSource{encoding_key_, o.suffix, size, color_.get(), work.planes});
        else if (work.share)
            claim = work.share->claim(SetShare::Source{pack_spec(o, *work.planes, preset_, size), color_.get(),
                                                       work.planes});
        const uint64_t cost = claim && !claim->leads() ? 0 : output_cost(o, size, preset_);
        tasks.post(cost, [this, &work, i] {
            write_one(work, i);
            if (auto& done = work.claims[i]) {  // its followers go on, with its bytes or their own
                work.share->settle(*done);
                done.reset();
            }
        });
    }
}

void Ingestor::write_one(SetWork& work, size_t i) const {
    const Planes& planes = *work.planes;
    SetShare::Claim* claim = work.claims[i].get();
    const auto batch_write = [&work](const std::string& rel, std::span<const unsigned char> b, std::string& e) {
        return work.batch->write(rel, b, e);
    };
    // 8-bit outputs of codes planes go from codes to codes; anything else through floats.
    const auto pack_encode = [&](const OutputSpec& o, Size size, std::vector<unsigned char>& bytes, std::string& sha,
                                 std::string& e) {
        const PackSpec spec = pack_spec(o, planes, preset_, size);
        auto fresh = [&] {
            const EncodeOptions enc{spec.format, spec.bit_depth};
            std::optional<Image8> packed8 = pack_output8(spec, planes, *color_);
            return packed8 ? encode_image(*packed8, enc, bytes, e)
                           : encode_image(pack_output(spec, planes, *color_), enc, bytes, e);
        };
        if (!claim) return fresh();
        return work.share->encode(*claim, fresh, bytes, sha);
    };
    const auto encode_blocks = [&](const OutputSpec& o, Size size, texture::EncodedOutput& out, std::string& e) {
        auto fresh = [&](texture::EncodedOutput& into) {
            return texture::encode_output(o, planes, size, {&preset_, color_.get(), std::string(kGenerator), 1}, into,
                                          e);
        };
        if (!claim) return fresh(out);
        return work.share->encode_blocks(*claim, fresh, out);
    };
    const auto refused = work.run.refused.find(work.src.name);
    const OutputJob job{preset_,
                        *color_,
                        work.plan,
                        planes,
                        work.src.name,
                        Size{work.plan.width, work.plan.height},
                        refused == work.run.refused.end() ? nullptr : &refused->second,
                        batch_write,
                        pack_encode,
                        encode_blocks};
    const OutputSpec& o = *work.wanted[i];
    Written& written = work.written[i];
    try {
        written = write_output(o, job);
    } catch (const std::bad_alloc&) {  // a task must not throw
        written.failure = finding(code::output_write_failed, "", "",
                                  preset_.output_path(work.src.name, o) +
                                      ": out of memory while packing or encoding it (" +
                                      std::to_string(work.plan.width) + "x" + std::to_string(work.plan.height) +
                                      "); run with fewer --jobs, or set the preset's max_size");
    } catch (const std::exception& e) {
        written.failure = finding(code::output_write_failed, "", "",
                                  preset_.output_path(work.src.name, o) + ": " + e.what());
    }
}

MaterialResult Ingestor::end(SetWork& work) const {
    if (work.restored) return std::move(*work.result);
    MaterialResult res = work.result ? std::move(*work.result) : finish_outputs(work);
    PresetRun& run = work.run;
    // Only a complete result records its key and is kept: a set with an output that could not be
    // written (partial), or one stopped by a signal, is not "unchanged" to plan --changed-since
    // and is computed again next time.
    const bool complete = !res.failure && res.entry.status == manifest::Status::ok && !stop_requested();
    if (work.action && complete) res.entry.key = *work.action;
    if (!work.key) return res;
    ++run.misses;
    std::string error;
    if (complete && !run.cache_off && !run.cache->store(*work.key, res.entry, opt_.out_dir, error) &&
        !run.cache_off.exchange(true))
        run.cache_problem(run.cache->dir().string() + ": cannot store results (" + error +
                          "); the cache is off for the rest of this run");
    return res;
}

MaterialResult Ingestor::finish_outputs(SetWork& work) const {
    MaterialResult res;
    SetPlan& plan = work.plan;
    std::vector<Written>& written = work.written;
    OutputFolder::Batch& batch = *work.batch;
    for (const auto& [rel, error] : batch.wait())
        for (auto& r : written)
            if (r.entry && r.entry->file == rel) {
                r.entry.reset();
                r.failure = finding(code::output_write_failed, "", "", error);
            }
    if (auto f = too_large(written)) plan.findings.push_back(std::move(*f));

    std::vector<manifest::Output> outputs;
    for (auto& r : written) {  // preset order, whatever finished first
        if (r.entry) outputs.push_back(std::move(*r.entry));
        if (r.failure) {
            plan.findings.push_back(std::move(*r.failure));
            plan.partial = true;
        }
        for (auto& f : r.notes) plan.findings.push_back(std::move(f));
    }
    const MaterialSource& src = work.src;
    manifest::Material& m = res.entry;
    m = material_entry(plan, src.name, source_of(src, opt_.out_dir), opt_.rules);
    m.outputs = std::move(outputs);
    if (src.is_zip) m.archive = relative_to(src.root, opt_.out_dir);
    m.emissive_strength = work.emissive_strength;
    decide_alpha(preset_, *work.planes, m);
    write_material_files(
        preset_,
        [&batch](const std::string& rel, std::span<const unsigned char> b, std::string& e) {
            return batch.write(rel, b, e);
        },
        m);
    for (const auto& [file, error] : batch.wait()) {
        const std::string& rel = file;  // a structured binding cannot be captured before C++20's P1091 (clang 14)
        std::erase_if(m.material_files, [&rel](const manifest::MaterialFile& f) { return f.file == rel; });
        m.findings.push_back(finding(code::output_write_failed, "", "", error));
        m.status = manifest::Status::partial;
    }
    return res;
}

namespace {

// The output folder, made when missing. Empty, or why it cannot be (a link to nothing).
std::string make_output_folder(const fs::path& out) {
    std::error_code ec;
    if (fs::is_symlink(fs::symlink_status(out, ec)) && !fs::exists(out, ec))
        return out.string() + ": a symbolic link to " + fs::read_symlink(out, ec).string() +
               ", which does not exist; create its target or choose another output folder";
    fs::create_directories(out, ec);
    if (ec || !fs::is_directory(out, ec))
        return out.string() + ": cannot create the output folder (" + ec.message() + ")";
    return {};
}

// Every output path is claimed before any set runs, in set order: two outputs that would be
// one file (a preset pattern that leaves names equal, names that differ in case only) are
// refused the same way every run, and none is written twice. Returns set -> suffix -> why not.
std::map<std::string, std::map<std::string, std::string>> claim_outputs(OutputFolder& folder, const Preset& preset,
                                                                        const std::string& manifest_name,
                                                                        const std::vector<MaterialSource>& sets) {
    std::map<std::string, std::map<std::string, std::string>> refused;
    for (const std::string& own : {manifest_name, folder.lock_name(), folder.journal_name()}) folder.claim(own, "");
    for (const auto& set : sets)
        for (const auto& o : preset.outputs) {
            const std::string rel = preset.output_path(set.name, o);
            if (std::string why = folder.claim(rel, set.name); !why.empty())
                refused[set.name][o.suffix] = rel + ": " + why;
        }
    return refused;
}

}  // namespace

std::optional<fs::path> preset_output_folder(const fs::path& out, const std::string& preset_name, size_t presets,
                                             std::set<std::string>& taken, std::string& error) {
    if (presets <= 1) return out;
    const std::string& folder = preset_name;
    if (folder.empty() || folder == "." || folder == ".." || folder.find_first_of("/\\") != std::string::npos) {
        error = "the preset's name \"" + folder + "\" cannot name its output folder; give it a plain name";
        return std::nullopt;
    }
    if (!taken.insert(folder).second) {
        error = "two presets of the run are named \"" + folder + "\"; each preset writes <out>/<its name>";
        return std::nullopt;
    }
    return out / folder;
}

IngestResult Ingestor::run(const std::vector<fs::path>& inputs) const {
    return std::move(run_together({this}, Batch::find(inputs, {opt_.out_dir})).front());
}

void Ingestor::PresetRun::open(const Batch& batch, std::string split_digest) {
    const IngestOptions& opt = ing.opt_;
    if (result.error = make_output_folder(opt.out_dir); !result.error.empty()) return;
    result.notes = batch.skipped;  // earlier output folders in the inputs
    if (!batch.output_conflict.empty()) {
        result.error = batch.output_conflict;
        result.usage_error = true;
        return;
    }
    // The folder is ours from here to the end (lock, journal): store/output_dir.hpp.
    folder = OutputFolder::open({opt.out_dir, opt.manifest_name, opt.force, ing.preset_.name, opt.replace},
                                result.error, result.usage_error);
    if (!folder) return;
    remove_stale_temps(opt.out_dir);  // a killed run's, never a running one's
    split = std::move(split_digest);
    refused = claim_outputs(*folder, ing.preset_, opt.manifest_name, batch.sets);
    if (!folder->begin(result.error)) return;
    // The cache never fails a run: one that cannot be opened is a problem reported, then off.
    if (opt.cache_dir) {
        std::string error;
        cache_store = Cache::create(*opt.cache_dir, error);
        if (cache_store) cache = &*cache_store;
        else result.cache_problems.push_back(error + "; running without the cache");
    }
    spool = manifest::MaterialSpool::open(opt.out_dir, result.error);
    ready = spool != nullptr;
}

void Ingestor::PresetRun::record(const MaterialSource& set, MaterialResult&& r, size_t total) {
    std::string error;
    const bool spooled = r.failure || spool->add(r.entry, error);
    ++done;
    if (ing.opt_.progress) ing.opt_.progress(done, total, set.name, r);
    if (!spooled) {
        if (spool_error.empty()) spool_error = error;
    } else if (r.failure) {
        result.manifest.failures.push_back({source_of(set, ing.opt_.out_dir), std::string(code::unreadable_file),
                                            *r.failure});
    } else {
        MaterialTally tally{r.entry.name, {}};
        validate::add_material(tally.findings, r.entry.findings);
        result.materials.push_back(std::move(tally));
        for (const auto& o : r.entry.outputs) produced.insert(o.file);
        for (const auto& f : r.entry.material_files) produced.insert(f.file);
    }
}

std::vector<IngestResult> Ingestor::run_together(const std::vector<const Ingestor*>& ingestors, Batch batch) {
    std::vector<std::unique_ptr<PresetRun>> runs;
    const IngestOptions& lead = ingestors.front()->opt_;
    // --shard I/N: every preset of the pass runs the same shard (the CLI gives them one), split
    // once; each records the split's digest under its own context.
    const std::optional<Batch::Split> split = lead.shard ? std::optional(batch.split(lead.shard->second))
                                                         : std::nullopt;
    std::vector<std::string> digests;
    for (const Ingestor* ing : ingestors) {
        auto& run = *runs.emplace_back(std::make_unique<PresetRun>(*ing));
        run.context = context_digest(ing->preset_, ing->opt_.rules, *ing->color_);
        digests.push_back(split ? batch.split_digest(*split, run.context) : std::string());
    }
    if (split) batch.keep_shard(*split, lead.shard->first);
    for (size_t t = 0; t < runs.size(); ++t) runs[t]->open(batch, std::move(digests[t]));
    const auto ready = static_cast<size_t>(std::count_if(runs.begin(), runs.end(),
                                                         [](const auto& r) { return r->ready; }));
    MemoryBudget budget(lead.memory_budget);
    // A core is spare while fewer sets run than there are workers: the batch's tail, a set alone,
    // or a worker waiting for the budget (a set larger than half of it runs beside no other).
    // A set's plan then decodes on two threads, and its outputs are written on two.
    const int workers = lead.jobs > 0 ? lead.jobs : static_cast<int>(std::max(1U, std::thread::hardware_concurrency()));
    std::atomic<int> in_flight{0};  // the pass's sets begun and not ended
    const std::function<bool()> spare_core = [&] { return in_flight.load() - budget.waiting() < workers; };
    std::mutex done_mutex;
    const std::vector<MaterialSource>& sets = batch.sets;
    const std::vector<size_t> order = batch.largest_first();
    parallel_for(ready > 0 ? sets.size() : 0, lead.jobs, [&](size_t k) {
        const size_t i = order[k];
        const InFlight counted(in_flight);
        std::optional<SetShare> share;  // several presets: one decode, one encode of equal outputs
        if (ready > 1) share.emplace(static_cast<int>(ready));
        auto record = [&](PresetRun& run, MaterialResult&& r) {
            std::lock_guard lock(done_mutex);
            run.record(sets[i], std::move(r), sets.size());
        };
        auto failure = [&](const std::exception* e) {  // exhaustion or a bug in one set must not stop the others
            MaterialResult r;
            r.failure = e ? sets[i].display + ": internal error: " + e->what()
                          : sets[i].display + ": out of memory while decoding or converting the set; run with "
                                              "fewer --jobs, or set the preset's max_size";
            return r;
        };
        std::vector<PresetRun*> todo;
        for (auto& run : runs)
            if (run->ready) todo.push_back(run.get());
        // The set's presets, kPresetsAtOnce at a time: each planned in turn (its maps decoded and
        // validated once, process/share.hpp), then the outputs of all of them, equal ones encoded
        // once, as tasks largest first on this worker and, while a core is spare, a second thread.
        for (size_t from = 0; from < todo.size(); from += kPresetsAtOnce) {
            const size_t to = std::min(todo.size(), from + kPresetsAtOnce);
            std::vector<std::unique_ptr<SetWork>> works(to - from);
            SpareTasks tasks(spare_core);
            bool stopped = false, leased = false;
            if (share) share->begin_claims();
            for (size_t t = from; t < to; ++t) {
                if (stop_requested()) {  // a signal asked to stop: no new set starts
                    stopped = true;
                    break;
                }
                // The first plan's lease covers its set's maps and planes; the next preset's planes
                // take the maps' place (made from them, moved where they are the plane as it is).
                const SetStage stage{leased || !lead.memory_budget ? nullptr : &budget, spare_core};
                std::optional<MaterialResult> r;
                try {
                    auto& work = works[t - from] = todo[t]->ing.begin(sets[i], stage, *todo[t],
                                                                      share ? &*share : nullptr);
                    leased = leased || (stage.budget && work->plan.lease);
                    todo[t]->ing.post_outputs(*work, tasks);
                } catch (const std::bad_alloc&) {
                    r = failure(nullptr);
                } catch (const std::exception& e) {
                    r = failure(&e);
                }
                if (!r) continue;
                tasks.run();  // (a task posted may read the work)
                if (works[t - from])
                    for (auto& claim : works[t - from]->claims)  // not posted: followers encode their own
                        if (claim) share->settle(*claim);
                works[t - from].reset();
                record(*todo[t], std::move(*r));
            }
            if (share) share->end_claims();
            tasks.run();
            for (size_t t = from; t < to; ++t) {
                if (!works[t - from]) continue;
                std::optional<MaterialResult> r;
                try {
                    r = todo[t]->ing.end(*works[t - from]);
                } catch (const std::bad_alloc&) {
                    r = failure(nullptr);
                } catch (const std::exception& e) {
                    r = failure(&e);
                }
                record(*todo[t], std::move(*r));
            }
            if (stopped) return;
        }
    });
    std::vector<IngestResult> results;
    for (auto& run : runs) {
        if (run->ready) run->finish(batch);
        results.push_back(std::move(run->result));
    }
    return results;
}

void Ingestor::PresetRun::finish(const Batch& batch) {
    const IngestOptions& opt = ing.opt_;
    const Preset& preset = ing.preset_;
    if (!spool_error.empty()) {
        result.error = spool_error;
        return;
    }
    manifest::Manifest& m = result.manifest;
    m.generator = std::string(kGenerator);
    m.preset = preset.name;
    m.normal_convention = preset.normal_convention;
    m.thresholds = rules::threshold_table(opt.rules.thresholds);
    if (opt.shard)
        m.shard = manifest::Manifest::Shard{opt.shard->first, opt.shard->second, context, split,
                                            static_cast<int>(batch.sets.size())};
    for (InputFailure f : batch.failures) {
        f.source = relative_to(f.source, opt.out_dir);
        m.failures.push_back(std::move(f));
    }
    spool->sort();  // names are unique: one folder each
    std::sort(result.materials.begin(), result.materials.end(),
              [](const auto& a, const auto& b) { return a.name < b.name; });
    // By source, then code and message: a total order, the one `matforge merge` writes too.
    std::sort(m.failures.begin(), m.failures.end(), [](const auto& a, const auto& b) {
        return std::tie(a.source, a.code, a.message) < std::tie(b.source, b.code, b.message);
    });

    result.cache_hits = hits;
    result.cache_misses = misses;
    for (auto& p : cache_problems) result.cache_problems.push_back(std::move(p));
    if (stop_requested()) {  // stopped: the journal stays, no manifest (the next run finishes the job)
        result.interrupted = true;
        return;
    }
    const WriteFile write_one = [&](const std::string& rel, std::span<const unsigned char> b, std::string& e) {
        return folder->write(rel, b, e);
    };
    // The folder's own files (every shard alike), then library.gltf and the other libraries:
    // every material of the run in one file (not per shard: a shard sees its part).
    if (!write_folder_files(preset, write_one, m.library, result.error) ||
        (!opt.shard &&
         !write_library(
             *spool, opt.out_dir, write_one,
             [&](const std::string& rel, const ByteProducer& p, std::string& e) { return folder->write(rel, p, e); },
             m.library, result.error)))
        return;
    for (const auto& f : m.library) produced.insert(f.file);
    std::string err;
    const ByteProducer text = [&](const ByteSink& sink) { return spool->write_manifest(m, sink, err); };
    if (!folder->finish(text, produced, result.notes, err)) result.error = err;
    remove_stale_temps(opt.out_dir);
}

}  // namespace mf
