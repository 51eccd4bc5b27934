#include "process/ingest.hpp"

#include <algorithm>
#include <map>
#include <mutex>
#include <set>
#include <thread>
#include <tuple>

#include "core/files.hpp"
#include "core/json.hpp"
#include "core/parallel.hpp"
#include "core/version.hpp"
#include "pack/pack.hpp"
#include "process/plan.hpp"
#include "process/work.hpp"

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

std::vector<manifest::Channel> manifest_channels(const std::vector<ChannelSpec>& channels) {
    std::vector<manifest::Channel> out;
    for (const auto& c : channels) {
        manifest::Channel m;
        m.key = c.key;
        m.role = c.role;
        m.value = c.value;
        switch (c.kind) {
            case ChannelSpec::Kind::role: m.kind = manifest::Channel::Kind::role; break;
            case ChannelSpec::Kind::smoothness: m.kind = manifest::Channel::Kind::smoothness; break;
            case ChannelSpec::Kind::constant: m.kind = manifest::Channel::Kind::constant; break;
            case ChannelSpec::Kind::unused: m.kind = manifest::Channel::Kind::unused; break;
        }
        out.push_back(std::move(m));
    }
    return out;
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

// Canonical planes per output role from the plan's routes (pack/pack.hpp's conventions). A
// decoded map is freed after its last plane is made: peak memory is one set's maps.
Planes make_planes(SetPlan& plan) {
    std::map<std::string, int> uses;
    for (const auto& [out, r] : plan.routes) ++uses[plan.inputs.at(r.from).file];
    Planes planes;
    for (const auto& [out, route] : plan.routes) {
        const std::string& file = plan.inputs.at(route.from).file;
        DecodedMap& l = plan.decoded.at(file);
        const bool last_use = --uses[file] == 0;
        RolePlane plane;
        Decoded& img = l.img;
        if (out == Role::albedo || out == Role::emissive) {
            if (img.is_codes()) plane.codes = last_use && img.codes.channels == 3 ? std::move(img.codes) : to_rgb(img.codes);
            else plane.image = last_use && img.floats.channels == 3 ? std::move(img.floats) : to_rgb(img.floats);
            plane.encoding = l.info.is_float ? ColorEncoding::linear : ColorEncoding::srgb;
        } else if (out == Role::normal) {
            // An empty blue is dropped: the two-channel path rebuilds Z from X and Y.
            if (plan.normal_z_rebuilt && img.channels() >= 3) {
                if (img.is_codes()) img.codes = first_two_channels(img.codes);
                else img.floats = first_two_channels(img.floats);
            }
            if (img.is_codes()) {  // decoded when packed (pack_output8) or resampled (fit_plane)
                plane.codes = last_use ? std::move(img.codes) : img.codes;
                plane.codes_convention = plan.normal_from();
            } else {
                decode_normal(img.floats, plan.normal_from(), plane.image);
            }
        } else {
            const int ch = route.channel < 0 ? 0 : route.channel;
            if (img.is_codes()) {
                plane.codes = last_use && img.codes.channels == 1 ? std::move(img.codes) : extract_channel(img.codes, ch);
                if (route.invert) invert(plane.codes);
            } else {
                plane.image = last_use && img.floats.channels == 1 ? std::move(img.floats) : extract_channel(img.floats, ch);
                if (route.invert) invert(plane.image);
            }
        }
        if (last_use) plan.decoded.erase(file);
        planes.emplace(out, std::move(plane));
    }
    plan.decoded.clear();  // planes hold what is needed from here on
    return planes;
}

// Set indices, largest input first (longest-processing-time scheduling): a 4K set started last
// would leave the other threads idle while it runs alone. Sizes come from the file system (a
// set inside a .zip counts its archive's size); results keep input order whatever this says.
std::vector<size_t> largest_first(const std::vector<MaterialSource>& sets) {
    std::vector<uint64_t> bytes;
    for (const auto& s : sets) bytes.push_back(set_bytes(s));
    std::vector<size_t> order(sets.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return bytes[a] > bytes[b]; });
    return order;
}

}  // namespace

Ingestor::Ingestor(Preset preset, std::shared_ptr<const ColorContext> color, IngestOptions opt)
    : preset_(std::move(preset)), color_(std::move(color)), opt_(std::move(opt)) {
    // --normal-convention overrides the preset everywhere: choice, conversion, encoding, manifest.
    if (opt_.normal_override) preset_.normal_convention = *opt_.normal_override;
}

MaterialResult Ingestor::process(const MaterialSource& src, MemoryBudget* budget) const {
    struct InFlight {  // counts this set as running until it returns or throws
        std::atomic<int>& n;
        explicit InFlight(std::atomic<int>& c) : n(c) { ++n; }
        ~InFlight() { --n; }
        InFlight(const InFlight&) = delete;
        InFlight& operator=(const InFlight&) = delete;
    } in_flight(in_flight_);
    MaterialResult res;
    SetPlan plan = plan_set(src, PlanOptions{&preset_, &opt_.rules, PlanMode::decode, budget});
    if (plan.failure) {
        res.failure = std::move(plan.failure);
        return res;
    }
    Planes planes = make_planes(plan);
    const int w = plan.width, h = plan.height;
    for (auto& [r, p] : planes) fit_plane(r, p, w, h, *color_);

    // Pack, encode, write.
    const fs::path mat_dir = opt_.out_dir / src.name;
    remove_stale_temps(mat_dir);
    struct Written {
        std::optional<manifest::Output> entry;  // set when written
        std::optional<Finding> failure;
    };
    std::vector<const OutputSpec*> wanted;
    for (const auto& o : preset_.outputs)
        if (output_needed(o, planes)) wanted.push_back(&o);
    std::vector<Written> written(wanted.size());
    auto write_output = [&](const OutputSpec& o) -> Written {
        auto failed = [](std::string msg) {
            return Written{std::nullopt, Finding{std::string(code::output_write_failed), Severity::error, "", "",
                                                 std::move(msg), {}}};
        };
        const std::string rel = preset_.output_path(src.name, o);
        const fs::path rel_path = fs::path(rel).lexically_normal();
        if (rel_path.is_absolute() || rel_path.empty() || *rel_path.begin() == "..")
            return failed("output path '" + rel + "' leaves the output folder; skipped");
        const auto roles = o.roles();
        const bool any_map = std::any_of(roles.begin(), roles.end(), [&](Role r) { return planes.count(r) > 0; });
        const Size size = any_map ? Size{w, h} : Size{preset_.constant_size, preset_.constant_size};
        // 8-bit outputs of codes planes go from codes to codes; anything else through floats.
        std::optional<Image8> packed8 = pack_output8(o, planes, preset_, size, *color_);
        const EncodeOptions enc{preset_.format, o.bit_depth};
        std::vector<unsigned char> bytes;
        std::string err;
        const bool encoded = packed8 ? encode_image(*packed8, enc, bytes, err)
                                     : encode_image(pack_output(o, planes, preset_, size, *color_), enc, bytes, err);
        packed8.reset();
        if (!encoded || !write_file_atomic(opt_.out_dir / rel_path, bytes, err)) return failed(rel + ": " + err);
        manifest::Output e;
        e.file = rel_path.generic_string();
        e.srgb = o.srgb;
        e.channels = manifest_channels(effective_channels(o, planes));
        if (std::find(roles.begin(), roles.end(), Role::normal) != roles.end())
            e.normal_convention = preset_.normal_convention;
        e.width = size.width;
        e.height = size.height;
        e.bit_depth = o.bit_depth;
        e.format = preset_.format;
        e.sha256 = sha256_hex(bytes);
        return Written{std::move(e), std::nullopt};
    };
    // The outputs of a large set are packed and encoded on two threads (each output on one:
    // deflate is serial) when a worker is idle, so a 4K set running alone (at the end of a batch,
    // or on its own) keeps both cores busy; with every worker busy that would only oversubscribe.
    const int workers = opt_.jobs > 0 ? opt_.jobs : static_cast<int>(std::max(1U, std::thread::hardware_concurrency()));
    const bool idle_worker = in_flight_.load() < workers;
    parallel_for(wanted.size(), plan.footprint > (uint64_t{64} << 20) && idle_worker ? 2 : 1, [&](size_t i) {
        try {
            written[i] = write_output(*wanted[i]);
        } catch (const std::exception& e) {  // parallel_for's fn must not throw (bad_alloc)
            written[i].failure = Finding{std::string(code::output_write_failed), Severity::error, "", "",
                                         preset_.output_path(src.name, *wanted[i]) + ": " + e.what(), {}};
        }
    });

    manifest::Material& m = res.entry;
    for (auto& r : written) {  // preset order, whatever finished first
        if (r.entry) m.outputs.push_back(std::move(*r.entry));
        if (r.failure) {
            plan.findings.push_back(std::move(*r.failure));
            plan.partial = true;
        }
    }
    m.name = src.name;
    m.source = source_of(src, opt_.out_dir);
    if (src.is_zip) m.archive = relative_to(src.root, opt_.out_dir);
    m.convention = plan.convention;
    m.status = plan.partial ? manifest::Status::partial : manifest::Status::ok;
    m.inputs = manifest_inputs(plan);
    m.constants = std::move(plan.constants);
    m.findings = std::move(plan.findings);
    return res;
}

IngestResult Ingestor::run(const std::vector<fs::path>& inputs) const {
    IngestResult result;
    std::error_code ec;
    fs::create_directories(opt_.out_dir, ec);
    if (ec || !fs::is_directory(opt_.out_dir, ec)) {
        result.error = opt_.out_dir.string() + ": cannot create the output folder (" + ec.message() + ")";
        return result;
    }
    std::vector<InputFailure> source_failures;
    std::vector<MaterialSource> sets = find_material_sets(inputs, opt_.out_dir, source_failures);
    if (opt_.shard) {  // this shard's sets only (process/work: stable, balanced by size)
        std::vector<uint64_t> bytes;
        for (const auto& s : sets) bytes.push_back(set_bytes(s));
        const std::vector<int> shard = assign_shards(sets, bytes, opt_.shard->second);
        std::vector<MaterialSource> mine;
        for (size_t i = 0; i < sets.size(); ++i)
            if (shard[i] == opt_.shard->first) mine.push_back(std::move(sets[i]));
        sets = std::move(mine);
    }

    std::vector<MaterialResult> results(sets.size());
    MemoryBudget budget(opt_.memory_budget);
    std::mutex progress_mutex;
    size_t done = 0;
    const std::vector<size_t> order = largest_first(sets);
    parallel_for(sets.size(), opt_.jobs, [&](size_t k) {
        const size_t i = order[k];
        try {
            results[i] = process(sets[i], opt_.memory_budget ? &budget : nullptr);
        } catch (const std::exception& e) {  // a bug or exhaustion in one set must not stop the others
            results[i] = MaterialResult{};
            results[i].failure = sets[i].display + ": internal error: " + e.what();
        }
        std::lock_guard lock(progress_mutex);
        ++done;
        if (opt_.progress) opt_.progress(done, sets.size(), sets[i].name, results[i]);
    });

    manifest::Manifest& m = result.manifest;
    m.generator = std::string(kGenerator);
    m.preset = preset_.name;
    m.normal_convention = preset_.normal_convention;
    for (size_t i = 0; i < sets.size(); ++i) {
        auto& r = results[i];
        if (r.failure) {
            m.failures.push_back({source_of(sets[i], opt_.out_dir), std::string(code::unreadable_file), *r.failure});
            continue;
        }
        m.materials.push_back(std::move(r.entry));
    }
    for (auto& f : source_failures) {
        f.source = relative_to(f.source, opt_.out_dir);
        m.failures.push_back(std::move(f));
    }
    std::sort(m.materials.begin(), m.materials.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
    // By source, then code and message: a total order, the one `matforge merge` writes too.
    std::sort(m.failures.begin(), m.failures.end(), [](const auto& a, const auto& b) {
        return std::tie(a.source, a.code, a.message) < std::tie(b.source, b.code, b.message);
    });

    const std::string text = json_text(manifest::to_json(m));  // never throws on non-UTF-8 names
    std::string err;
    if (!write_file_atomic(opt_.out_dir / opt_.manifest_name,
                           std::span(reinterpret_cast<const unsigned char*>(text.data()), text.size()), err))
        result.error = err;
    remove_stale_temps(opt_.out_dir);
    return result;
}

}  // namespace mf
